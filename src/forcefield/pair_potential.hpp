#pragma once
// The contract of a radial pair potential, used by non-bonded terms and by two-particle bonds: a
// host+device functor with
//   template <class R> struct Params { ... };   // plain, copyable to the device
//   template <class R> static SMD_HD PairTerm<R> evaluate(R r2, const Params<R>& p);
// returning U'(r)/r and U(r). The force on i from j is F_i = (U'(r)/r) r_ij with r_ij = r_j - r_i,
// and F_j = -F_i. A potential usable as a NonBonded entry also has
//   template <class R> static Params<R> make_pair_params(double epsilon, double sigma, double cutoff,
//                                                        bool shift);
// (cutoff = cutOffFactor x sigma; a zero cutoff means "does not interact"), and one usable as a Bond2
// entry has
//   template <class R> static Params<R> make_bond_params(const double* values, const Constants& c);
// with the values in the order its reader lists them. A potential of charges (Debye-Hueckel) instead
// has `static constexpr bool uses_charges = true` and evaluate(r2, p, q_i q_j).
#include <cmath>

#include "core/hd.hpp"

namespace structmd {

template <class R>
struct PairTerm {
    R dudr_over_r;
    R energy;
};

// Physical constants of the input's units, for potentials that need them.
struct Constants {
    double boltzmann = 1.0;
    double electricConversion = 1.0;
};

}  // namespace structmd
