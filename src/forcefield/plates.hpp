#pragma once
// Two moving plates normal to z. At time t the separation is S = s + 2 v t clamped to [S_min, S_max], and
// the plates stand at z_top = S/2 and z_bot = -S/2. Each particle feels
//   U = eps [(sigma / (z_top - z))^12 + (sigma / (z - z_bot))^12],   F = -dU/dz e_z,
// the exact gradient (the reference drops a factor 12 from the force). The particle radius plays no part.
#include <limits>

#include "forcefield/external_potential.hpp"

namespace structmd {

struct Plates {
    template <class R>
    struct Params {
        R separation;  // at t = 0
        R velocity;    // each plate moves outwards at this speed; negative compresses
        R min_separation;
        R max_separation;
        R epsilon;
        R sigma;
    };

    static std::vector<Parameter> parameters() {
        return {number("platesSeparation", "length", Must::be_positive),
                with_default(number("platesEpsilon", "energy"), 1.0),
                with_default(number("platesSigma", "length"), 1.0),
                with_default(number("compressionVelocity", "length/time"), 0.0),
                with_default(number("minPlatesSeparation", "length"), 0.0),
                with_default(number("maxPlatesSeparation", "length"), std::numeric_limits<double>::infinity())};
    }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        return make_params<R>(v["platesSeparation"], v["platesEpsilon"], v["platesSigma"], v["compressionVelocity"],
                              v["minPlatesSeparation"], v["maxPlatesSeparation"]);
    }

    template <class R>
    static Params<R> make_params(double platesSeparation, double platesEpsilon, double platesSigma,
                                 double compressionVelocity, double minPlatesSeparation, double maxPlatesSeparation) {
        return {R(platesSeparation),    R(compressionVelocity), R(minPlatesSeparation),
                R(maxPlatesSeparation), R(platesEpsilon),       R(platesSigma)};
    }

    template <class R>
    static SMD_HD SMD_INLINE R separation_at(const Params<R>& p, R time) {
        const R s = p.separation + R(2) * p.velocity * time;
        return s < p.min_separation ? p.min_separation : (s > p.max_separation ? p.max_separation : s);
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(Vec3<R> r, R, const Params<R>& p, R time, Vec3<R>& force) {
        const R top = R(0.5) * separation_at(p, time);
        const R inv_top = R(1) / (top - r.z);
        const R inv_bottom = R(1) / (r.z + top);
        const R top_term = twelfth_power(p.sigma * inv_top);
        const R bottom_term = twelfth_power(p.sigma * inv_bottom);
        // d/dz of (sigma/(z_top - z))^12 is +12 top_term / (z_top - z), of (sigma/(z - z_bot))^12 it is
        // -12 bottom_term / (z - z_bot).
        force = {R(0), R(0), R(12) * p.epsilon * (bottom_term * inv_bottom - top_term * inv_top)};
        return p.epsilon * (top_term + bottom_term);
    }

private:
    template <class R>
    static SMD_HD SMD_INLINE R twelfth_power(R x) {
        const R x3 = x * x * x;
        const R x6 = x3 * x3;
        return x6 * x6;
    }
};

}  // namespace structmd
