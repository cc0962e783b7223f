#pragma once
// External constant force: F = constantForce on every particle, U = 0 (the field does no bookkeeping of
// the work it does).
#include "forcefield/external_potential.hpp"

namespace structmd {

struct ExternalConstantForce {
    template <class R>
    struct Params {
        Vec3<R> force;
    };

    static std::vector<Parameter> parameters() { return {numbers("constantForce", 3, "force")}; }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        const std::array<double, 3> f = v.vec3("constantForce");
        return make_params<R>(Vec3<double>{f[0], f[1], f[2]});
    }

    template <class R>
    static Params<R> make_params(Vec3<double> constantForce) {
        return {{R(constantForce.x), R(constantForce.y), R(constantForce.z)}};
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(Vec3<R>, R, const Params<R>& p, R, Vec3<R>& force) {
        force = p.force;
        return R(0);
    }
};

}  // namespace structmd
