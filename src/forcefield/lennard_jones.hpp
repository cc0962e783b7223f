#pragma once
// Lennard-Jones pair potential of type 1: U(r) = 4 eps [(s/r)^12 - (s/r)^6] for r <= r_c, else 0.
// The energy jumps at r_c unless shift is set, which subtracts U(r_c) (structmd extension).
#include "forcefield/pair_potential.hpp"

namespace structmd {

struct LennardJonesType1 {
    template <class R>
    struct Params {
        R epsilon;
        R sigma2;
        R cutoff2;  // 0 for a type pair that does not interact
        R shift;    // U(r_c) when shifted, else 0
    };

    template <class R>
    static Params<R> make_params(double epsilon, double sigma, double cutoff, bool shifted) {
        const double sr6 = std::pow(sigma / cutoff, 6);
        const double shift = shifted ? 4.0 * epsilon * (sr6 * sr6 - sr6) : 0.0;
        return {R(epsilon), R(sigma * sigma), R(cutoff * cutoff), R(shift)};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        const R inv_r2 = R(1) / r2;
        const R sr2 = p.sigma2 * inv_r2;
        const R sr6 = sr2 * sr2 * sr2;
        PairTerm<R> term;
        // U'(r)/r = (24 eps / r^2) [(s/r)^6 - 2 (s/r)^12]
        term.dudr_over_r = R(24) * p.epsilon * inv_r2 * (sr6 - R(2) * sr6 * sr6);
        term.energy = R(4) * p.epsilon * (sr6 * sr6 - sr6) - p.shift;
        return term;
    }
};

}  // namespace structmd
