#pragma once
// Steric repulsion U(r) = eps (s/r)^n, n = 6 (Steric6) or 12 (Steric12). As a NonBonded entry it is cut
// at r_c (shift subtracts U(r_c)); as a Bond2 it has no cutoff.
#include <limits>

#include "core/real_limits.hpp"
#include "forcefield/pair_potential.hpp"

namespace structmd {

template <int Exponent>
struct Steric : EpsilonSigmaPair<Steric<Exponent>> {
    static constexpr bool under_domains = true;  // reader_entries.hpp: runs_under_domains
    using EpsilonSigmaPair<Steric<Exponent>>::make_pair_params;
    static_assert(Exponent > 0 && Exponent % 2 == 0, "the power is taken of (s/r)^2");

    template <class R>
    struct Params {
        R epsilon;
        R sigma2;
        R cutoff2;  // 0 for a type pair that does not interact, +infinity for a bond
        R shift;    // U(r_c) when shifted, else 0
    };

    template <class R>
    static Params<R> make_pair_params(double epsilon, double sigma, double cutoff, bool shifted) {
        if (!(cutoff > 0.0)) return {R(0), R(0), R(0), R(0)};
        const double shift = shifted ? epsilon * std::pow(sigma / cutoff, Exponent) : 0.0;
        return {R(epsilon), R(sigma * sigma), R(cutoff * cutoff), R(shift)};
    }

    static std::vector<Parameter> bond_parameters() { return Steric::pair_parameters(); }

    // A bond has no cutoff.
    template <class R>
    static Params<R> make_bond_params(const ParameterValues& v, const Constants&) {
        return {R(v["epsilon"]), R(v["sigma"] * v["sigma"]), std::numeric_limits<R>::infinity(), R(0)};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        PairTerm<R> term{R(0), R(0)};
        if (!(r2 < p.cutoff2)) return term;
        const R inv_r2 = reciprocal(r2);
        const R sr2 = p.sigma2 * inv_r2;
        R srn = sr2;
        for (int k = 1; k < Exponent / 2; ++k) srn *= sr2;
        const R u = p.epsilon * srn;
        // U'(r)/r = -n U / r^2
        term.dudr_over_r = R(-Exponent) * u * inv_r2;
        term.energy = u - p.shift;
        return term;
    }
};

using Steric6 = Steric<6>;
using Steric12 = Steric<12>;

}  // namespace structmd
