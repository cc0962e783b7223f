#pragma once
// FENE two-body bond: U(r) = -1/2 K R0^2 ln(1 - ((r - r0)/R0)^2) for |r - r0| < R0. Beyond that the
// bond is broken and no finite energy exists: the result is NaN, which the engine reports as a
// numerical error naming the step and particle.
#include <limits>

#include "forcefield/pair_potential.hpp"

namespace structmd {

struct FeneBond {
    template <class R>
    struct Params {
        R r0;
        R K;
        R R0;
    };

    static std::vector<Parameter> bond_parameters() {
        return {number("r0", "length"), number("K", "energy/length^2"), number("R0", "length", Must::be_positive)};
    }
    template <class R>
    static Params<R> make_bond_params(const ParameterValues& v, const Constants&) {
        return {R(v["r0"]), R(v["K"]), R(v["R0"])};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        const R r = sqrt(r2);
        const R x = (r - p.r0) / p.R0;
        const R remaining = R(1) - x * x;
        PairTerm<R> term;
        if (!(remaining > R(0))) {
            term.dudr_over_r = term.energy = std::numeric_limits<R>::quiet_NaN();
            return term;
        }
        // U'(r) = K (r - r0) / (1 - x^2)
        term.dudr_over_r = r > R(0) ? p.K * (r - p.r0) / (remaining * r) : R(0);
        term.energy = R(-0.5) * p.K * p.R0 * p.R0 * log(remaining);
        return term;
    }
};

}  // namespace structmd
