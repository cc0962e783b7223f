#pragma once
// A particle tied to a fixed point p by a harmonic spring: U = 1/2 K (d - r0)^2, d = |d_vec| with
// d_vec the minimum image of p - r[0]; the force K (d - r0) d_vec / d pulls the particle towards
// distance r0 from p. With r0 = 0 the force is K d_vec, smooth through d = 0 (the minimum of U). With
// r0 != 0 the spring has no direction at d = 0 and the force there is taken as zero: every direction is
// equally valid and U = 1/2 K r0^2 is finite.
#include "forcefield/bond_potential.hpp"

namespace structmd {

struct FixedHarmonic {
    static constexpr int arity = 1;

    template <class R>
    struct Params {
        R K;
        R r0;
        Vec3<R> point;
    };

    static std::vector<Parameter> parameters() {
        return {number("K", "energy/length^2"), number("r0", "length"), numbers("position", 3, "length")};
    }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        const std::array<double, 3> point = v.vec3("position");
        return {R(v["K"]), R(v["r0"]), {R(point[0]), R(point[1]), R(point[2])}};
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const Params<R>& p, const Box<R>& box, Vec3<R>* force) {
        // wrap() folds any difference into the box, so the point need not lie inside it.
        const Vec3<R> to_point = box.wrap(p.point - r[0]);
        const R d = sqrt(dot(to_point, to_point));
        const R stretch = d - p.r0;
        // r0 = 0: F = K d_vec, with no division, so that its derivative (the Hessian K I) holds at d = 0 too.
        const R scale = p.r0 == R(0) ? p.K : d > R(0) ? p.K * stretch / d : R(0);
        force[0] = scale * to_point;
        return R(0.5) * p.K * stretch * stretch;
    }
};

}  // namespace structmd
