#pragma once
// The contract of a radial pair potential, used by non-bonded terms and by two-particle bonds: a
// host+device functor with
//   template <class R> struct Params { ... };   // plain, copyable to the device
//   template <class R> static SMD_HD PairTerm<R> evaluate(R r2, const Params<R>& p);
// returning U'(r)/r and U(r). The force on i from j is F_i = (U'(r)/r) r_ij with r_ij = r_j - r_i,
// and F_j = -F_i. A potential usable as a NonBonded entry also declares its parameters and builds
// its Params from them by name:
//   static std::vector<Parameter> pair_parameters();   // columns of the entry's per-type-pair table
//   static std::vector<Parameter> entry_parameters();  // given once in the entry's "parameters"
//   template <class R> static Params<R> make_pair_params(const ParameterValues& v, const Constants& c,
//                                                        double cutOffFactor, bool shift);
// (a Params whose cutoff2 is 0 does not interact). A potential without per-type-pair parameters
// applies to every type pair. One usable as a Bond2 entry has
//   static std::vector<Parameter> bond_parameters();
//   template <class R> static Params<R> make_bond_params(const ParameterValues& v, const Constants& c);
// A potential of charges (Debye-Hueckel) has `static constexpr bool uses_charges = true` and
// evaluate(r2, p, q_i q_j).
#include <cmath>
#include <vector>

#include "core/hd.hpp"
#include "core/parameters.hpp"
#include "forcefield/pair_term.hpp"

namespace structmd {

// Physical constants of the input's units, for potentials that need them.
struct Constants {
    double boltzmann = 1.0;
    double electricConversion = 1.0;
};

// The pair parameters of the Lennard-Jones-like family: epsilon and sigma per type pair, cut at
// cutOffFactor x sigma. Potential has make_pair_params<R>(epsilon, sigma, cutoff, shift).
template <class Potential>
struct EpsilonSigmaPair {
    static std::vector<Parameter> pair_parameters() {
        return {number("epsilon", "energy"), number("sigma", "length", Must::be_positive)};
    }
    static std::vector<Parameter> entry_parameters() { return {}; }

    template <class R>
    static auto make_pair_params(const ParameterValues& v, const Constants&, double cutOffFactor, bool shift) {
        return Potential::template make_pair_params<R>(v["epsilon"], v["sigma"], cutOffFactor * v["sigma"], shift);
    }
};

}  // namespace structmd
