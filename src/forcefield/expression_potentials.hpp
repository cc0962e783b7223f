#pragma once
// The functors of the Expression components: the energy of a compiled expression (src/expression/)
// of r, theta, phi or x, y, z and its exact derivative, run by the bytecode interpreter on the host
// and in CUDA kernels alike, in the precision of the term (PairR for pairs, R otherwise). Each
// Params points to its program in backend memory, which the interactor owns, and holds the values
// of its data columns (per type pair or per bond). Forces follow from the derivative exactly as in
// the built-in terms of the same variable: RadialBond for r, HarmonicAngle for theta, Dihedral for
// phi (bonded_geometry.hpp), and -grad U for an external field.
#include "expression/interpreter.hpp"
#include "forcefield/bond_potential.hpp"
#include "forcefield/bonded_geometry.hpp"
#include "forcefield/dihedral.hpp"
#include "forcefield/external_potential.hpp"
#include "forcefield/pair_potential.hpp"

namespace structmd {

// NonBonded: U(r) + offset for r < cutOff (offset = -U(cutOff) when shifted), 0 beyond.
struct ExpressionPair {
    template <class R>
    struct Params {
        R cutoff2;  // 0: the type pair does not interact
        R offset;
        expression::ProgramView<R> program;
        R columns[expression::kMaxColumns];
    };

    template <class R>
    static SMD_HD SMD_INLINE PairTerm<R> evaluate(R r2, const Params<R>& p) {
        const R r = sqrt(r2);
        R out[2];
        expression::run_program(p.program, &r, p.columns, out);
        return {out[1] / r, out[0] + p.offset};
    }
};

// Bond2 of r = |r1 - r0|, Bond3 of the angle theta at the middle particle, Bond4 of the dihedral phi.
template <int N>
struct ExpressionBond {
    static_assert(N >= 2 && N <= 4, "expression bonds have 2, 3 or 4 particles");
    static constexpr int arity = N;

    template <class R>
    struct Params {
        expression::ProgramView<R> program;
        R columns[expression::kMaxColumns];
    };

    template <class R>
    static SMD_HD SMD_INLINE R compute(const Vec3<R>* r, const Params<R>& p, const Box<R>&, Vec3<R>* force) {
        R out[2];
        if constexpr (N == 2) {
            const Vec3<R> d = r[1] - r[0];
            const R length = sqrt(dot(d, d));
            expression::run_program(p.program, &length, p.columns, out);
            force[0] = (out[1] / length) * d;
            force[1] = -force[0];
        } else if constexpr (N == 3) {
            const bonded_geometry::BondAngle<R> angle = bonded_geometry::bond_angle(r[0] - r[1], r[2] - r[1]);
            expression::run_program(p.program, &angle.theta, p.columns, out);
            force[0] = (-out[1]) * angle.dtheta_da;
            force[2] = (-out[1]) * angle.dtheta_db;
            force[1] = -(force[0] + force[2]);
        } else {
            const bonded_geometry::DihedralAngle<R> angle = dihedral_detail::angle_of(r);
            expression::run_program(p.program, &angle.phi, p.columns, out);
            dihedral_detail::write_forces<R>(angle, out[1], force);
        }
        return out[0];
    }
};

// External: U(x, y, z, t) of the particle's wrapped position and the simulation time.
struct ExpressionExternal {
    template <class R>
    struct Params {
        expression::ProgramView<R> program;
    };

    template <class R>
    static SMD_HD SMD_INLINE R compute(Vec3<R> r, R, const Params<R>& p, R time, Vec3<R>& force) {
        const R inputs[4] = {r.x, r.y, r.z, time};
        R out[4];
        expression::run_program(p.program, inputs, static_cast<const R*>(nullptr), out);
        force = {-out[1], -out[2], -out[3]};
        return out[0];
    }
};

}  // namespace structmd
