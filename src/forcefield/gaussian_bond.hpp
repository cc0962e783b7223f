#pragma once
// Gaussian two-body bond: U(r) = -E exp(-(r - r0)^2 / (2D)), E the well depth, D a variance (length^2).
#include "forcefield/pair_potential.hpp"

namespace structmd {

struct GaussianBond {
    template <class R>
    struct Params {
        R depth;
        R r0;
        R inverse_variance;
    };

    static std::vector<Parameter> bond_parameters() {
        return {number("E", "energy"), number("r0", "length"), number("D", "length^2", Must::be_positive)};
    }
    template <class R>
    static Params<R> make_bond_params(const ParameterValues& v, const Constants&) {
        return {R(v["E"]), R(v["r0"]), R(1.0 / v["D"])};
    }

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        const R r = sqrt(r2);
        const R stretch = r - p.r0;
        const R energy = -p.depth * exp(R(-0.5) * stretch * stretch * p.inverse_variance);
        PairTerm<R> term;
        // U'(r) = -U (r - r0) / D. r = 0 has no direction: the force there is taken as zero rather than NaN.
        term.dudr_over_r = r > R(0) ? -energy * stretch * p.inverse_variance / r : R(0);
        term.energy = energy;
        return term;
    }
};

}  // namespace structmd
