#pragma once
// A spherical shell of centre c whose radius at time t is R(t) = R + v t clamped to [R_min, R_max]. A
// particle of radius a at distance d = |r - c| from the centre (r the wrapped position, no periodic
// image) feels
//   U = eps [(sigma + a) / (d - R(t))]^12,   F = -grad U = 12 U / ((d - R(t)) d) (r - c),
// the exact gradient (the reference leaves the radius out of the force). At the centre the direction is
// undefined and the force is taken as zero.
#include <limits>

#include "forcefield/external_potential.hpp"

namespace structmd {

struct SphericalShell {
    template <class R>
    struct Params {
        Vec3<R> center;
        R radius;  // at t = 0
        R velocity;
        R min_radius;
        R max_radius;
        R epsilon;
        R sigma;
    };

    static std::vector<Parameter> parameters() {
        return {numbers("shellCenter", 3, "length"),
                number("shellRadius", "length", Must::be_positive),
                with_default(number("shellEpsilon", "energy"), 1.0),
                with_default(number("shellSigma", "length"), 1.0),
                with_default(number("minShellRadius", "length"), 0.0),
                with_default(number("maxShellRadius", "length"), std::numeric_limits<double>::infinity()),
                with_default(number("radiusVelocity", "length/time"), 0.0)};
    }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        const std::array<double, 3> c = v.vec3("shellCenter");
        return make_params<R>({c[0], c[1], c[2]}, v["shellRadius"], v["shellEpsilon"], v["shellSigma"],
                              v["minShellRadius"], v["maxShellRadius"], v["radiusVelocity"]);
    }

    template <class R>
    static Params<R> make_params(Vec3<double> shellCenter, double shellRadius, double shellEpsilon, double shellSigma,
                                 double minShellRadius, double maxShellRadius, double radiusVelocity) {
        return {{R(shellCenter.x), R(shellCenter.y), R(shellCenter.z)},
                R(shellRadius),
                R(radiusVelocity),
                R(minShellRadius),
                R(maxShellRadius),
                R(shellEpsilon),
                R(shellSigma)};
    }

    template <class R>
    static SMD_HD SMD_INLINE R radius_at(const Params<R>& p, R time) {
        const R radius = p.radius + p.velocity * time;
        return radius < p.min_radius ? p.min_radius : (radius > p.max_radius ? p.max_radius : radius);
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(Vec3<R> r, R particle_radius, const Params<R>& p, R time, Vec3<R>& force) {
        const Vec3<R> offset = r - p.center;
        const R distance = sqrt(dot(offset, offset));
        const R inv_gap = R(1) / (distance - radius_at(p, time));
        const R q = (p.sigma + particle_radius) * inv_gap;
        const R q3 = q * q * q;
        const R energy = p.epsilon * (q3 * q3) * (q3 * q3);
        const R scale = distance > R(0) ? R(12) * energy * inv_gap / distance : R(0);
        force = scale * offset;
        return energy;
    }
};

}  // namespace structmd
