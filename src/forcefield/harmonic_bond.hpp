#pragma once
// Harmonic two-body bond: U(r) = 1/2 K (r - r0)^2.
#include "forcefield/pair_potential.hpp"

namespace structmd {

struct HarmonicBond {
    template <class R>
    struct Params {
        R K;
        R r0;
    };

    static std::vector<Parameter> bond_parameters() {
        return {number("K", "energy/length^2"), number("r0", "length")};
    }
    template <class R>
    static Params<R> make_bond_params(const ParameterValues& v, const Constants&) {
        return {R(v["K"]), R(v["r0"])};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        const R r = sqrt(r2);
        const R stretch = r - p.r0;
        PairTerm<R> term;
        // r = 0 has no direction; the force there is taken as zero rather than NaN.
        term.dudr_over_r = r > R(0) ? p.K * stretch / r : R(0);
        term.energy = R(0.5) * p.K * stretch * stretch;
        return term;
    }
};

}  // namespace structmd
