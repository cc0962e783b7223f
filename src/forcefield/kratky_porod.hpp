#pragma once
// Kratky-Porod (worm-like chain) bending of three particles: U = K (1 + cos theta), theta the angle
// at the middle particle r[1] between r[0] - r[1] and r[2] - r[1]; a straight chain (theta = pi) has
// U = 0 and no force. U is smooth in the positions, including at theta = 0 and pi. A zero-length
// arm gives NaN (no angle exists).
#include "forcefield/bond_potential.hpp"

namespace structmd {

struct KratkyPorod {
    static constexpr int arity = 3;

    template <class R>
    struct Params {
        R K;
    };

    static std::vector<Parameter> parameters() { return {number("K", "energy")}; }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        return {R(v["K"])};
    }

    // U as a function of cos theta = a.b / (|a| |b|) alone (a = r[0] - r[1], b = r[2] - r[1]): its
    // gradient, d cos/da = b / (|a| |b|) - cos a / |a|^2, needs no angle and so no trigonometry, and
    // is exactly zero at theta = 0 and pi. A zero-length arm makes 1 / |a| infinite and cos NaN.
    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const Params<R>& p, const Box<R>&, Vec3<R>* force) {
        const Vec3<R> a = r[0] - r[1];
        const Vec3<R> b = r[2] - r[1];
        const R aa = dot(a, a);
        const R bb = dot(b, b);
        const R inverse_lengths = (R(1) / sqrt(aa)) * (R(1) / sqrt(bb));
        const R cosine = dot(a, b) * inverse_lengths;
        force[0] = (-p.K) * (inverse_lengths * b - (cosine / aa) * a);
        force[2] = (-p.K) * (inverse_lengths * a - (cosine / bb) * b);
        force[1] = -(force[0] + force[2]);
        return p.K * (R(1) + cosine);
    }
};

}  // namespace structmd
