#pragma once
// The interaction terms of the Expression components, generic in how the expression is evaluated:
// a Function gives the energy and its derivatives with respect to the inputs,
//   template <class R> struct Params { ... };   // the values of the data columns, and what it runs
//   template <class R> static SMD_HD void evaluate(const R* inputs, const Params<R>& p, R* outputs);
// with outputs[0] = U and outputs[1 + k] = dU/d inputs[k]. The bytecode interpreter is one Function
// (expression_potentials.hpp, the CPU backend); the expression emitted as source and compiled at
// load time is another (expression_compiled.hpp, CUDA). Forces follow from the derivative as in the
// built-in terms of the same variable: RadialBond for r, HarmonicAngle for theta, Dihedral for phi
// (bonded_geometry.hpp), and -grad U for an external field. Free of the standard library, so that
// kernels compiled at run time include it.
#include "core/box.hpp"
#include "core/hd.hpp"
#include "core/vec.hpp"
#include "forcefield/bonded_geometry.hpp"
#include "forcefield/pair_term.hpp"

namespace structmd {

// NonBonded: U(r) + offset for r < cutOff (offset = -U(cutOff) when shifted), 0 beyond.
template <class Function>
struct ExpressionPair {
    template <class R>
    struct Params {
        R cutoff2;  // 0: the type pair does not interact
        R offset;
        typename Function::template Params<R> function;
    };

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        const R r = sqrt(r2);
        R out[2];
        Function::evaluate(&r, p.function, out);
        return {out[1] / r, out[0] + p.offset};
    }
};

// Bond2 of r = |r1 - r0|, Bond3 of the angle theta at the middle particle, Bond4 of the dihedral phi.
template <int N, class Function>
struct ExpressionBond {
    static_assert(N >= 2 && N <= 4, "expression bonds have 2, 3 or 4 particles");
    static constexpr int arity = N;

    template <class R>
    using Params = typename Function::template Params<R>;

    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const Params<R>& p, const Box<R>&, Vec3<R>* force) {
        R out[2];
        if constexpr (N == 2) {
            const Vec3<R> d = r[1] - r[0];
            const R length = sqrt(dot(d, d));
            Function::evaluate(&length, p, out);
            force[0] = (out[1] / length) * d;
            force[1] = -force[0];
        } else if constexpr (N == 3) {
            const bonded_geometry::BondAngle<R> angle = bonded_geometry::bond_angle(r[0] - r[1], r[2] - r[1]);
            Function::evaluate(&angle.theta, p, out);
            force[0] = (-out[1]) * angle.dtheta_da;
            force[2] = (-out[1]) * angle.dtheta_db;
            force[1] = -(force[0] + force[2]);
        } else {
            const bonded_geometry::DihedralAngle<R> angle = bonded_geometry::dihedral_of(r);
            Function::evaluate(&angle.phi, p, out);
            bonded_geometry::write_dihedral_forces<R>(angle, out[1], force);
        }
        return out[0];
    }
};

// External: U(x, y, z, t) of the particle's wrapped position and the simulation time.
template <class Function>
struct ExpressionExternal {
    template <class R>
    using Params = typename Function::template Params<R>;

    template <class R>
    static SMD_HD SMD_INLINE R compute(Vec3<R> r, R, const Params<R>& p, R time, Vec3<R>& force) {
        const R inputs[4] = {r.x, r.y, r.z, time};
        R out[4];
        Function::evaluate(inputs, p, out);
        force = {-out[1], -out[2], -out[3]};
        return out[0];
    }
};

}  // namespace structmd
