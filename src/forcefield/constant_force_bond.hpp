#pragma once
// A constant force on one particle (Bond1 ConstantForce): F = the given vector, U = 0 (the input
// format assigns this term no energy, so F is not -grad U).
#include "forcefield/bond_potential.hpp"

namespace structmd {

struct ConstantForceBond {
    static constexpr int arity = 1;

    template <class R>
    struct Params {
        Vec3<R> force;
    };

    static std::vector<Parameter> parameters() { return {numbers("force", 3, "force")}; }
    template <class R>
    static Params<R> make_params(const ParameterValues& v, const Constants&) {
        const std::array<double, 3> f = v.vec3("force");
        return {{R(f[0]), R(f[1]), R(f[2])}};
    }

    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>*, const Params<R>& p, const Box<R>&, Vec3<R>* force) {
        force[0] = p.force;
        return R(0);
    }
};

}  // namespace structmd
