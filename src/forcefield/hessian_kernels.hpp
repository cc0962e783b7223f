#pragma once
// Second derivatives of the force field, one column of 3x3 blocks at a time: for a chosen particle s
// ("the seed"), the block of each particle j is H[j] = d2U / dx_s dx_j (row: the seed's axis,
// column: j's). Each term's own functor is evaluated in dual numbers (core/dual.hpp) seeded on the
// seed's coordinates, so the derivative of its forces is exact and no second formula exists to keep
// in step with the first. Only the seed's neighbours, and the bonds it is in, contribute.
#include "core/dual.hpp"
#include "core/hd.hpp"
#include "core/vec.hpp"
#include "forcefield/external_kernel.hpp"
#include "forcefield/pair_kernel.hpp"
#include "forcefield/seed_traversal.hpp"
#include "state/step_clock.hpp"

namespace structmd {

template <class R>
SMD_HD SMD_INLINE Vec3<Dual<R>> constant_dual(Vec3<R> a) {
    return {Dual<R>(a.x, R(0)), Dual<R>(a.y, R(0)), Dual<R>(a.z, R(0))};
}

// a with unit derivative along `axis`: the seed displaced along that axis.
template <class R>
SMD_HD SMD_INLINE Vec3<Dual<R>> seeded_dual(Vec3<R> a, int axis) {
    Vec3<Dual<R>> d = constant_dual(a);
    (axis == 0 ? d.x : axis == 1 ? d.y : d.z).d = R(1);
    return d;
}

template <class R>
SMD_HD SMD_INLINE Box<Dual<R>> constant_dual(const Box<R>& box) {
    return {constant_dual(box.length), constant_dual(box.inverse)};
}

// Row `axis` of the block: minus the derivative of the force f (a dual vector seeded on that axis).
template <class R>
SMD_HD SMD_INLINE void subtract_force_derivative(Tensor3<R>& h, int axis, const Vec3<Dual<R>>& f) {
    R* row = axis == 0 ? &h.xx : axis == 1 ? &h.yx : &h.zx;
    row[0] -= f.x.d;
    row[1] -= f.y.d;
    row[2] -= f.z.d;
}

// A radial pair term U(r) with g = U'(r)/r: the seed s and each neighbour j at d = r_j - r_s add
// B = 2 g' d d^T + g I (g' = dg/d(r^2)) to H[s] and -B to H[j]. g' is the dual part of g evaluated at
// the dual r^2 = (r2, 1).
template <class Potential, class R, class PairR>
struct PairHessianKernel {
    using Params = typename Potential::template Params<Dual<PairR>>;
    const R* charge;
    const R* radius;
    const uint8_t* group;
    NeighbourView<R> neighbours;
    PairTable<Params> table;
    int seed;
    Tensor3<R>* blocks;

    SMD_HD void operator()(int64_t k) const {
        Tensor3<R> self = zero_tensor<R>();
        bool hasPartners = false;
        for_each_partner_of_seed<Dual<PairR>>(neighbours, k, seed, group, table,
                                              [&](int j, const Vec3<R>& d, const Params& p) {
            const PairTerm<Dual<PairR>> t =
                evaluate_pair_of<Potential>(Dual<PairR>(PairR(dot(d, d)), PairR(1)), p, charge, radius, seed, j);
            const R g = R(t.dudr_over_r.v);
            Tensor3<R> b = (R(2) * R(t.dudr_over_r.d)) * outer(d, d);
            b.xx += g;
            b.yy += g;
            b.zz += g;
            self += b;
            blocks[j] += R(-1) * b;
            hasPartners = true;
        });
        if (hasPartners) blocks[seed] += self;
    }
};

// A bonded term of N particles: for particle i in a bond with the seed, minus the derivative of the
// force on i as the seed moves along each axis.
template <class Potential, class R>
struct BondHessianKernel {
    static constexpr int N = Potential::arity;
    using Params = typename Potential::template Params<Dual<R>>;
    BondsAroundSeed<N, R, Params> bonds;
    Tensor3<R>* blocks;

    SMD_HD void operator()(int64_t i) const {
        Tensor3<R> h = zero_tensor<R>();
        const Box<Dual<R>> dualBox = constant_dual(bonds.box);
        bonds.for_each_of(i, [&](const Params& params, int slot, int seedSlot, const Vec3<R>* r) {
            for (int axis = 0; axis < 3; ++axis) {
                Vec3<Dual<R>> rd[N];
                for (int m = 0; m < N; ++m) rd[m] = m == seedSlot ? seeded_dual(r[m], axis) : constant_dual(r[m]);
                Vec3<Dual<R>> force[N];
                Potential::compute(rd, params, dualBox, force);
                subtract_force_derivative(h, axis, force[slot]);
            }
        });
        blocks[i] += h;
    }
};

// A field on a particle at position x: its own block, minus the derivative of its force.
template <class Potential, class R>
SMD_HD SMD_INLINE Tensor3<R> field_block(Vec3<R> x, R radius, const typename Potential::template Params<Dual<R>>& p,
                                         R time) {
    Tensor3<R> h = zero_tensor<R>();
    for (int axis = 0; axis < 3; ++axis) {
        Vec3<Dual<R>> f{Dual<R>(0), Dual<R>(0), Dual<R>(0)};
        Potential::compute(seeded_dual(x, axis), Dual<R>(radius), p, Dual<R>(time), f);
        subtract_force_derivative(h, axis, f);
    }
    return h;
}

// A field on each particle alone: only the seed's own block.
template <class Potential, class R>
struct ExternalHessianKernel {
    using Params = typename Potential::template Params<Dual<R>>;
    const Real4<R>* pos;
    const R* radius;
    const uint8_t* group;
    Params params;
    ClockView now;
    int seed;
    Tensor3<R>* blocks;

    SMD_HD void operator()(int64_t) const {
        if (group && !group[seed]) return;
        blocks[seed] += field_block<Potential>(xyz(pos[seed]), radius[seed], params, R(now.time()));
    }
};

// The same for a field of per-type parameters (TypedExternalKernel's table, in dual numbers).
template <class Potential, class R>
struct TypedExternalHessianKernel {
    using Params = typename Potential::template Params<Dual<R>>;
    TypedField<R, Params> field;
    int seed;
    Tensor3<R>* blocks;

    SMD_HD void operator()(int64_t) const {
        const Params* params = field.entry_of(seed);
        if (!params) return;
        blocks[seed] += field_block<Potential>(xyz(field.pos[seed]), field.radius[seed], *params, R(field.now.time()));
    }
};

}  // namespace structmd
