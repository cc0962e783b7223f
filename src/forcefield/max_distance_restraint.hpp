#pragma once
// A restraint that lets two particles move freely up to a largest distance and pulls them back
// harmonically beyond it (a flat-bottomed harmonic bond open towards r = 0):
//   U(r) = 1/2 K (r - maxDistance)^2   for r > maxDistance,   0 otherwise.
// U and its first derivative are continuous at maxDistance (the second derivative jumps from 0 to K).
// maxDistance >= 0, so the force never needs the direction of a zero-length bond.
#include "forcefield/pair_potential.hpp"

namespace structmd {

struct MaxDistanceRestraint {
    template <class R>
    struct Params {
        R K;
        R maxDistance;
    };

    static std::vector<Parameter> bond_parameters() {
        return {number("K", "energy/length^2"), number("maxDistance", "length", Must::be_non_negative)};
    }
    template <class R>
    static Params<R> make_bond_params(const ParameterValues& v, const Constants&) {
        return {R(v["K"]), R(v["maxDistance"])};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        PairTerm<R> term;
        term.energy = R(0);
        term.dudr_over_r = R(0);
        if (r2 > p.maxDistance * p.maxDistance) {  // then r > 0
            const R r = sqrt(r2);
            const R stretch = r - p.maxDistance;
            term.dudr_over_r = p.K * stretch / r;
            term.energy = R(0.5) * p.K * stretch * stretch;
        }
        return term;
    }
};

}  // namespace structmd
