#pragma once
// UAMMD-structured's ["Surface","WCA_PlainCylinder"]: a flat solid filling z < z0 (plainPosition),
// pierced by a cylindrical well of radius R (cylinderRadius) around the z axis that goes down for
// ever. The space a particle may occupy is z >= z0 anywhere, and rho < R below z0 (rho = sqrt(x^2 +
// y^2)). A particle feels the WCA type 1 potential of its distance to the nearest point of the solid,
// with an epsilon and a sigma per type:
//   U = 4 eps [(sigma/g)^12 - (sigma/g)^6] + eps   for g < 2^(1/6) sigma, else 0
// where g = |v| and v runs from that nearest point to the particle:
//   above the plane, outside the well (z >= z0, rho >= R)   v = (0, 0, z - z0)            the plane
//   inside the well, below the plane (z < z0, rho < R)      v = (rho - R) e_rho           its wall
//   above the well's mouth (z >= z0, rho < R)               v = (rho - R) e_rho + (z - z0) e_z   its rim
// g is continuous across these regions, and F = -dU/dg v/g. On the axis (rho = 0) e_rho is undefined
// and the force has no x, y part (every direction of the rim is equally near). Inside the solid (z <
// z0, rho >= R) no distance is defined: U = 0 and F = 0, as the reference's force (its energy there
// divides by zero).
#include <vector>

#include "forcefield/external_potential.hpp"
#include "forcefield/lennard_jones.hpp"

namespace structmd {

struct WCAPlainCylinder {
    template <class R>
    struct Params {
        R plane;   // z0
        R radius;  // R
        LennardJonesParams<R> wca;
    };

    static std::vector<Parameter> parameters() {
        return {with_default(number("plainPosition", "length"), 0.0),
                number("cylinderRadius", "length", Must::be_non_negative)};
    }
    static std::vector<Parameter> type_parameters() {
        return {number("epsilon", "energy"), number("sigma", "length", Must::be_positive)};
    }

    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        return make_params<R>(v["plainPosition"], v["cylinderRadius"], v["epsilon"], v["sigma"]);
    }

    template <class R>
    static Params<R> make_params(double plainPosition, double cylinderRadius, double epsilon, double sigma) {
        const double cutoff = LennardJonesShape1::minimum_distance(sigma);
        return {R(plainPosition), R(cylinderRadius), {R(epsilon), R(sigma * sigma), R(cutoff * cutoff), R(epsilon)}};
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(Vec3<R> r, R, const Params<R>& p, R, Vec3<R>& force) {
        force = {R(0), R(0), R(0)};
        const R rho = sqrt(r.x * r.x + r.y * r.y);
        const bool in_well = rho < p.radius;
        const bool above = r.z >= p.plane;
        if (!in_well && !above) return R(0);               // inside the solid
        const R radial = in_well ? rho - p.radius : R(0);  // v along e_rho
        const R vertical = above ? r.z - p.plane : R(0);   // v along e_z
        const PairTerm<R> term =
            evaluate_lennard_jones<LennardJonesShape1>(radial * radial + vertical * vertical, p.wca);
        // F = -(dU/dg / g) v; dudr_over_r is dU/dg / g.
        if (rho > R(0)) {
            const R in_plane = -term.dudr_over_r * radial / rho;
            force.x = in_plane * r.x;
            force.y = in_plane * r.y;
        }
        force.z = -term.dudr_over_r * vertical;
        return term.energy;
    }
};

}  // namespace structmd
