#pragma once
// UAMMD-structured's ["AFM","SphericallyBluntedConicTip"]: the AFM of afm_tip.hpp (chip spring, chip
// motion, one tip particle per row and its sample) with a tip shaped as a cone of half-angle theta
// (tipAngle, radians) pointing down -z, blunted by the sphere of the tip particle's radius R to which
// it is tangent. A sample particle at d = r_j - r_tip (rho = |(d_x, d_y)|, h = d_z) feels
//   U = eps (sigma / g)^12,   F = -dU/dg grad g,
// g its distance to the tip's surface: with s = rho sin(theta) + h cos(theta) (where along the cone's
// side the particle's foot falls, 0 on the circle where sphere and cone touch),
//   g = |d| - R                                    for s <= 0 (the spherical cap),
//   g = rho cos(theta) - h sin(theta) - R          for s > 0  (the cone's side),
// which meet with their gradients on s = 0. UAMMD-structured takes the horizontal distance to the
// cone (rho - |h + R/sin(theta)| tan(theta)), splits the regions on the plane h = -R sin(theta), which
// leaves a jump in U there, and its z force on the side has the wrong sign; here g is the distance
// to the surface and F its exact gradient.
#include <cmath>
#include <string>
#include <vector>

#include "forcefield/afm_tip.hpp"

namespace structmd {

struct SphericallyBluntedConicTipPotential {
    template <class R>
    struct Params {
        R epsilon, sigma;
        R sinTheta, cosTheta;
    };

    static std::vector<Parameter> parameters() {
        return {number("epsilon", "energy"), number("sigma", "length", Must::be_positive),
                number("tipAngle", "radians", Must::be_positive)};
    }
    // Checked per row by the reader: a half-angle of a cone that points down.
    static std::string check(const ParameterValues& v) {
        return v["tipAngle"] < M_PI / 2 ? "" : "tipAngle must be below pi/2 (a cone's half-angle, in radians)";
    }
    template <class R>
    static Params<R> make_params(const ParameterValues& v) {
        const double theta = v["tipAngle"];
        return {R(v["epsilon"]), R(v["sigma"]), R(std::sin(theta)), R(std::cos(theta))};
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(Vec3<R> d, R tipRadius, const Params<R>& p, Vec3<R>& force) {
        const R rho = sqrt(d.x * d.x + d.y * d.y);
        const R along = rho * p.sinTheta + d.z * p.cosTheta;
        R g;
        Vec3<R> gradient{R(0), R(0), R(0)};
        if (along <= R(0)) {
            const R r = sqrt(dot(d, d));
            g = r - tipRadius;
            if (r > R(0)) gradient = (R(1) / r) * d;
        } else {
            g = rho * p.cosTheta - d.z * p.sinTheta - tipRadius;
            // On the axis (inside the tip) rho has no gradient; its part is taken as zero there.
            if (rho > R(0)) gradient = {p.cosTheta * d.x / rho, p.cosTheta * d.y / rho, R(0)};
            gradient.z = -p.sinTheta;
        }
        const R s2 = p.sigma * p.sigma / (g * g);
        const R s6 = s2 * s2 * s2;
        const R energy = p.epsilon * s6 * s6;
        force = (R(12) * energy / g) * gradient;
        return energy;
    }
};

}  // namespace structmd
