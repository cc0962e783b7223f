#pragma once
// Morse two-body bond: U(r) = E [(1 - exp(-(r - r0)/D))^2 - 1], E the well depth, D a width (length).
#include "forcefield/pair_potential.hpp"

namespace structmd {

struct MorseBond {
    template <class R>
    struct Params {
        R r0;
        R depth;
        R inverse_width;
    };

    static std::vector<Parameter> bond_parameters() {
        return {number("r0", "length"), number("E", "energy"), number("D", "length", Must::be_positive)};
    }
    template <class R>
    static Params<R> make_bond_params(const ParameterValues& v, const Constants&) {
        return {R(v["r0"]), R(v["E"]), R(1.0 / v["D"])};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        const R r = sqrt(r2);
        const R decay = exp(-(r - p.r0) * p.inverse_width);
        PairTerm<R> term;
        // U = E (x^2 - 2x) with x = exp(-(r - r0)/D), so U'(r) = 2 E x (1 - x) / D. r = 0 has no
        // direction: the force there is taken as zero rather than NaN.
        term.dudr_over_r = r > R(0) ? R(2) * p.depth * decay * (R(1) - decay) * p.inverse_width / r : R(0);
        term.energy = p.depth * decay * (decay - R(2));
        return term;
    }
};

}  // namespace structmd
