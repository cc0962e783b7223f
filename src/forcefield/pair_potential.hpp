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
// evaluate(r2, p, q_i q_j); one of particle radii has `static constexpr bool uses_radii = true` and
// evaluate(r2, p, a_i, a_j); one of both, evaluate(r2, p, q_i q_j, a_i, a_j). Optionally:
//   static constexpr const char* cutoff_key;  // the entry reads no cutOffFactor; its range is set by
//                                             // this member of the entry ("parameters.gamma", "data")
//   static constexpr bool under_domains = true;  // it runs under spatial domains: it reads of a
//                                                // neighbour only what a domain's ghosts carry
//   template <class R> static Params<R> make_unlisted_pair_params(const ParameterValues& shared,
//                                                                 const Constants& c, double cutOffFactor,
//                                                                 bool shift);
// the Params of the type pairs the table does not list (without it, those do not interact).
#include <cmath>
#include <type_traits>
#include <vector>

#include "core/hd.hpp"
#include "core/parameters.hpp"
#include "forcefield/pair_term.hpp"

namespace structmd {

// What potentials take from the system besides their parameters: the physical constants of the
// input's units, the largest particle radius (the range of a potential of radii scales with it), the
// ensemble's temperature (a term given in units of k_B T scales with it) and where the ensemble's
// coupling parameter lambda lives on the backend (Particles::lambda): simulation steps change it
// during a run, so a term of lambda keeps this pointer and reads the value at each evaluation.
struct Constants {
    double boltzmann = 1.0;
    double electricConversion = 1.0;
    double largestRadius = 0.0;
    double temperature = 0.0;  // k_B T = boltzmann * temperature
    const double* lambda = nullptr;  // set by the engine; null while the input is only read

    double kT() const { return boltzmann * temperature; }
};

// A potential whose constants are numbers in one unit system declares
//   static constexpr const char* required_units;   // "KcalMol_A"
// and an input in other units is refused.
template <class Potential, class = void>
struct has_required_units : std::false_type {};
template <class Potential>
struct has_required_units<Potential, std::void_t<decltype(Potential::required_units)>> : std::true_type {};

template <class Potential>
const char* required_units_of() {
    if constexpr (has_required_units<Potential>::value)
        return Potential::required_units;
    else
        return "";
}

template <class Potential, class = void>
struct has_cutoff_key : std::false_type {};
template <class Potential>
struct has_cutoff_key<Potential, std::void_t<decltype(Potential::cutoff_key)>> : std::true_type {};

// Potentials with named choices among their entry parameters declare `static std::vector<TextOption>
// text_options()`.
template <class Potential, class = void>
struct has_text_options : std::false_type {};
template <class Potential>
struct has_text_options<Potential, std::void_t<decltype(Potential::text_options())>> : std::true_type {};

// A potential of no cutoff (Coulomb, Gravity) declares `static constexpr bool infinite_range = true`:
// it runs over all pairs only (an ["NBody", "all"] list), in a box open along every axis.
template <class Potential, class = void>
struct has_infinite_range : std::false_type {};
template <class Potential>
struct has_infinite_range<Potential, std::void_t<decltype(Potential::infinite_range)>>
    : std::bool_constant<Potential::infinite_range> {};

template <class Potential, class = void>
struct acts_on_unlisted_pairs : std::false_type {};
template <class Potential>
struct acts_on_unlisted_pairs<Potential,
                              std::void_t<decltype(&Potential::template make_unlisted_pair_params<double>)>>
    : std::true_type {};

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
