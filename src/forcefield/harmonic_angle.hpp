#pragma once
// Harmonic angle of three particles: U = 1/2 K (theta - theta0)^2, theta the angle at the middle
// particle r[1] between r[0] - r[1] and r[2] - r[1] (a straight chain has theta = pi).
// theta comes from atan2 and stays exact near 0 and pi. There theta itself is not differentiable;
// at exactly 0 or pi the force is zero when theta0 equals theta, and otherwise has its finite
// one-sided limit, of magnitude K |theta - theta0| / |r[0] - r[1]| on r[0], along a bending plane
// fixed by the first arm (bonded_geometry.hpp). A zero-length arm gives NaN (no angle exists).
#include "forcefield/bond_potential.hpp"
#include "forcefield/bonded_geometry.hpp"

namespace structmd {

struct HarmonicAngle {
    static constexpr int arity = 3;

    template <class R>
    struct Params {
        R K;
        R theta0;
    };

    static std::vector<Parameter> parameters() {
        return {number("K", "energy/radian^2"), number("theta0", "radian")};
    }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        return {R(v["K"]), R(v["theta0"])};
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const Params<R>& p, const Box<R>&, Vec3<R>* force) {
        const bonded_geometry::BondAngle<R> angle = bonded_geometry::bond_angle(r[0] - r[1], r[2] - r[1]);
        const R deviation = angle.theta - p.theta0;
        const R dudtheta = p.K * deviation;
        force[0] = (-dudtheta) * angle.dtheta_da;
        force[2] = (-dudtheta) * angle.dtheta_db;
        force[1] = -(force[0] + force[2]);
        return R(0.5) * p.K * deviation * deviation;
    }
};

}  // namespace structmd
