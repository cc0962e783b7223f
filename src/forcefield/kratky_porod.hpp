#pragma once
// Kratky-Porod (worm-like chain) bending of three particles: U = K (1 + cos theta), theta the angle
// at the middle particle r[1] between r[0] - r[1] and r[2] - r[1]; a straight chain (theta = pi) has
// U = 0 and no force. U is smooth in the positions, including at theta = 0 and pi. A zero-length
// arm gives NaN (no angle exists).
#include "forcefield/bond_potential.hpp"
#include "forcefield/bonded_geometry.hpp"

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

    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const Params<R>& p, const Box<R>&, Vec3<R>* force) {
        const bonded_geometry::BondAngle<R> angle = bonded_geometry::bond_angle(r[0] - r[1], r[2] - r[1]);
        // dU/dtheta = -K sin(theta) vanishes at 0 and pi, where the gradient of theta has its limit
        // direction: the product is the exact (zero) gradient there.
        const R dudtheta = -p.K * sin(angle.theta);
        force[0] = (-dudtheta) * angle.dtheta_da;
        force[2] = (-dudtheta) * angle.dtheta_db;
        force[1] = -(force[0] + force[2]);
        return p.K * (R(1) + cos(angle.theta));
    }
};

}  // namespace structmd
