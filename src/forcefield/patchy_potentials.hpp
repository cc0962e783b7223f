#pragma once
// The interactions between the patches of patchy particles (UAMMD-structured's NonBondedPatches and
// SurfacePatches families), as pure functions of one patch pair or one patch:
//
//   switch s(r)    = (1 + cos(pi r / rc)) / 2 for r <= rc, 0 beyond: 1 at contact, 0 at rc
//   stiffness mask m(x; K) = x / (x + K (1 - x)): keeps m(0) = 0 and m(1) = 1, steeper for larger K
//   orientation    o(A, B; R) = (1 + tr((A^T B)^T R)) / 4, in [0, 1], 1 when A^T B = R
//
//   ["NonBondedPatches","DistanceSwitchCosine"]  U = -E m(s(r); K)
//   ["NonBondedPatches","COSRAP"]                U = -E m(s(r); Kswt) m(o(A, B; R); Krap)
//   ["SurfacePatches","Linker"]                  U = -epsilon exp(-(z - z0)^2 / (2 sigma))
//
// r: the patch-patch distance (minimum image); A, B: the rotation matrices of the two parents (their
// body axes as columns, core/quaternion.hpp); R: the pair's relative rotation (a quaternion
// parameter). A pair function returns the pair energy, the force on the first patch and the torque
// that the orientation term alone exerts on the first patch's parent (lab frame); the caller adds
// the lever-arm torque of the force. Free of the standard library (kernels only).
#include "core/hd.hpp"
#include "core/quaternion.hpp"
#include "core/vec.hpp"

namespace structmd {

namespace patch_math {

template <class R>
SMD_HD SMD_INLINE R stiffness_mask(R x, R K) {
    return x / (x + K * (R(1) - x));
}
template <class R>
SMD_HD SMD_INLINE R stiffness_mask_derivative(R x, R K) {
    const R d = x + K * (R(1) - x);
    return K / (d * d);
}

// m(s(r); K) and its derivative with respect to r, for r <= rc.
template <class R>
SMD_HD SMD_INLINE R cosine_switch(R r, R rc, R K, R& derivative) {
    const R pi = R(3.14159265358979323846);
    const R s = R(0.5) * (R(1) + cos(pi * r / rc));
    derivative = stiffness_mask_derivative(s, K) * (R(-0.5) * pi / rc) * sin(pi * r / rc);
    return stiffness_mask(s, K);
}

// The body axes (columns of the rotation matrix) of a unit quaternion.
template <class R>
struct Frame {
    Vec3<R> x, y, z;
};
template <class R>
SMD_HD SMD_INLINE Frame<R> frame_of(const Real4<R>& q) {
    return {body_x(q), body_y(q), body_z(q)};
}
template <class R>
SMD_HD SMD_INLINE Vec3<R> cross(Vec3<R> a, Vec3<R> b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// M v, for M given by its columns.
template <class R>
SMD_HD SMD_INLINE Vec3<R> apply(const Frame<R>& m, Vec3<R> v) {
    return v.x * m.x + v.y * m.y + v.z * m.z;
}

}  // namespace patch_math

// One patch-pair term's result: the pair energy, the force on the first patch, and the torque of the
// orientation dependence on the first patch's parent.
template <class R>
struct PatchPairTerm {
    R energy;
    Vec3<R> force;
    Vec3<R> torque;
};

struct DistanceSwitchCosinePatch {
    template <class R>
    struct Params {
        R E, K, rc;
    };

    // rij: from patch i to patch j; the orientations are not read.
    template <class R>
    static SMD_HD SMD_INLINE PatchPairTerm<R> evaluate(Vec3<R> rij, const Real4<R>&, const Real4<R>&, const Params<R>& p) {
        PatchPairTerm<R> t{R(0), {R(0), R(0), R(0)}, {R(0), R(0), R(0)}};
        const R r2 = dot(rij, rij);
        if (r2 > p.rc * p.rc) return t;
        const R r = sqrt(r2);
        R dsdr;
        const R s = patch_math::cosine_switch(r, p.rc, p.K, dsdr);
        t.energy = -p.E * s;
        // dU/dx_i = -E s'(r) (-rij / r); s'(0) = 0, so coincident patches feel no force.
        if (r > R(0)) t.force = (-p.E * dsdr / r) * rij;
        return t;
    }
};

struct CosrapPatch {
    template <class R>
    struct Params {
        R E, Kswt, Krap, rc;
        Real4<R> rotation;  // R of the pair (type of i, type of j), a unit quaternion
    };

    template <class R>
    static SMD_HD SMD_INLINE PatchPairTerm<R> evaluate(Vec3<R> rij, const Real4<R>& qi, const Real4<R>& qj,
                                                      const Params<R>& p) {
        using namespace patch_math;
        PatchPairTerm<R> t{R(0), {R(0), R(0), R(0)}, {R(0), R(0), R(0)}};
        const R r2 = dot(rij, rij);
        if (r2 > p.rc * p.rc) return t;
        const R r = sqrt(r2);
        R dsdr;
        const R s = cosine_switch(r, p.rc, p.Kswt, dsdr);
        // tr((A^T B)^T R) = <A, B R^T>_F = sum_k a_k . g_k, with g_k the columns of G = B R^T.
        const Frame<R> a = frame_of(qi), b = frame_of(qj), rot = frame_of(p.rotation);
        // Column k of G = B R^T is B times row k of R, and row k of R is (rot.x_k, rot.y_k, rot.z_k).
        const Vec3<R> g0 = apply(b, Vec3<R>{rot.x.x, rot.y.x, rot.z.x});
        const Vec3<R> g1 = apply(b, Vec3<R>{rot.x.y, rot.y.y, rot.z.y});
        const Vec3<R> g2 = apply(b, Vec3<R>{rot.x.z, rot.y.z, rot.z.z});
        const R o = (R(1) + dot(a.x, g0) + dot(a.y, g1) + dot(a.z, g2)) / R(4);
        const R orientation = stiffness_mask(o, p.Krap);
        t.energy = -p.E * s * orientation;
        if (r > R(0)) t.force = (-p.E * dsdr * orientation / r) * rij;
        // Turning A by dtheta (a_k -> a_k + dtheta x a_k) changes o by dtheta . sum_k (a_k x g_k) / 4,
        // so the torque -dU/dtheta is E s m'(o) sum_k (a_k x g_k) / 4.
        const Vec3<R> dodtheta = R(0.25) * (cross(a.x, g0) + cross(a.y, g1) + cross(a.z, g2));
        t.torque = (p.E * s * stiffness_mask_derivative(o, p.Krap)) * dodtheta;
        return t;
    }
};

struct LinkerPatch {
    template <class R>
    struct Params {
        R epsilon, sigma, surface;  // sigma enters as UAMMD-structured uses it: a variance (length^2)
    };

    // The energy of a patch at height z, and the force along z on it.
    template <class R>
    static SMD_HD SMD_INLINE R evaluate(R z, const Params<R>& p, R& forceZ) {
        const R dz = z - p.surface;
        const R e = -p.epsilon * exp(-dz * dz / (R(2) * p.sigma));
        forceZ = e * dz / p.sigma;  // -dU/dz
        return e;
    }
};

}  // namespace structmd
