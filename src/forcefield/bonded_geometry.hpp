#pragma once
// Geometry shared by the angle and dihedral terms: the bond angle and the IUPAC dihedral angle with
// their gradients, each computed once so that every functor of that angle uses the same robust form.
// Free of the standard library: kernels compiled at run time (expression bonds on CUDA) include it.
#include "core/hd.hpp"
#include "core/real_limits.hpp"
#include "core/vec.hpp"

namespace structmd {
namespace bonded_geometry {

template <class R>
SMD_HD SMD_INLINE Vec3<R> cross(Vec3<R> a, Vec3<R> b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// A vector perpendicular to a (a != 0), chosen from a alone: a crossed with the axis along which a is
// shortest, so the result is never close to zero.
template <class R>
SMD_HD SMD_INLINE Vec3<R> perpendicular_to(Vec3<R> a) {
    const R ax = fabs(a.x), ay = fabs(a.y), az = fabs(a.z);
    if (ax <= ay && ax <= az) return {R(0), a.z, -a.y};  // a x (1, 0, 0)
    if (ay <= az) return {-a.z, R(0), a.x};              // a x (0, 1, 0)
    return {a.y, -a.x, R(0)};                            // a x (0, 0, 1)
}

template <class R>
struct BondAngle {
    R theta;             // in [0, pi]
    Vec3<R> dtheta_da;   // gradient of theta with respect to a
    Vec3<R> dtheta_db;   // and to b
};

// The angle theta between arms a and b (both nonzero), from atan2(|a x b|, a.b), which keeps full
// precision near 0 and pi where acos does not. theta decreases as either arm turns towards the
// other inside their plane, so dtheta/da = -u_a / |a| with u_a the unit vector normal to a, in the
// plane, towards b (and likewise for b).
// At theta exactly 0 or pi the plane, hence the gradient, is undefined and theta is not
// differentiable. There (and wherever |a x b| is below the rounding of a x b, so that its direction
// is noise) the plane is replaced by one fixed by a alone (normal = perpendicular_to(a)): the
// gradient is then the one-sided limit reached as the end of b leaves the line along normal x a. It is
// finite, has |dtheta/da| = 1/|a|, and keeps forces summing to zero with zero torque.
// An arm of zero length leaves theta undefined: theta and the gradient are NaN.
template <class R>
SMD_HD SMD_INLINE BondAngle<R> bond_angle(Vec3<R> a, Vec3<R> b) {
    const R aa = dot(a, a);
    const R bb = dot(b, b);
    Vec3<R> normal = cross(a, b);
    const R normal_length = sqrt(dot(normal, normal));
    BondAngle<R> angle;
    if (!(aa > R(0) && bb > R(0))) {
        const R nan = quiet_nan<R>();
        angle.theta = nan;
        angle.dtheta_da = angle.dtheta_db = {nan, nan, nan};
        return angle;
    }
    angle.theta = atan2(normal_length, dot(a, b));
    if (normal_length <= machine_epsilon<R>() * sqrt(aa * bb)) normal = perpendicular_to(a);
    const R inverse_normal_length = R(1) / sqrt(dot(normal, normal));
    const Vec3<R> unit_normal = inverse_normal_length * normal;
    angle.dtheta_da = (R(-1) / aa) * cross(unit_normal, a);
    angle.dtheta_db = (R(-1) / bb) * cross(b, unit_normal);
    return angle;
}

template <class R>
struct DihedralAngle {
    R phi;                  // in [-pi, pi]
    Vec3<R> dphi_dr[4];     // gradient of phi with respect to each of the four positions
};

// The IUPAC dihedral angle of the chain r0-r1-r2-r3 from its bond vectors b1 = r1 - r0,
// b2 = r2 - r1, b3 = r3 - r2: phi = atan2(|b2| b1.(b2 x b3), (b1 x b2).(b2 x b3)); phi = 0 when r0
// and r3 are on the same side (cis), pi for trans, and positive when, looking from r1 towards r2,
// the bond to r0 turns clockwise to eclipse the bond to r3.
// The gradient is the analytic one (Blondel and Karplus 1996): the end particles move normal to
// their planes, dphi/dr0 = -|b2| m / |m|^2, dphi/dr3 = |b2| n / |n|^2 (m = b1 x b2, n = b2 x b3),
// and the middle ones take what makes the sum and the torque zero.
// If r0, r1, r2 or r1, r2, r3 are collinear (|m| or |n| below the rounding of the cross product,
// |b2| = 0 included) the dihedral is undefined and its gradient diverges: phi is taken as 0 and the
// gradient as zero, so such a chain feels no dihedral force and a finite energy.
template <class R>
SMD_HD SMD_INLINE DihedralAngle<R> dihedral_angle(Vec3<R> b1, Vec3<R> b2, Vec3<R> b3) {
    const Vec3<R> m = cross(b1, b2);
    const Vec3<R> n = cross(b2, b3);
    const R mm = dot(m, m);
    const R nn = dot(n, n);
    const R b1b1 = dot(b1, b1);
    const R b2b2 = dot(b2, b2);
    const R b3b3 = dot(b3, b3);
    const R eps2 = machine_epsilon<R>() * machine_epsilon<R>();
    DihedralAngle<R> angle;
    if (!(mm > eps2 * b1b1 * b2b2) || !(nn > eps2 * b2b2 * b3b3)) {
        angle.phi = R(0);
        for (int k = 0; k < 4; ++k) angle.dphi_dr[k] = {R(0), R(0), R(0)};
        return angle;
    }
    const R b2_length = sqrt(b2b2);
    angle.phi = atan2(b2_length * dot(b1, n), dot(m, n));
    const Vec3<R> g0 = (-b2_length / mm) * m;
    const Vec3<R> g3 = (b2_length / nn) * n;
    const R p = dot(b1, b2) / b2b2;
    const R q = dot(b3, b2) / b2b2;
    angle.dphi_dr[0] = g0;
    angle.dphi_dr[1] = (-(R(1) + p)) * g0 + q * g3;
    angle.dphi_dr[2] = p * g0 - (R(1) + q) * g3;
    angle.dphi_dr[3] = g3;
    return angle;
}

// The dihedral of the chain r[0]-r[1]-r[2]-r[3].
template <class R>
SMD_HD SMD_INLINE DihedralAngle<R> dihedral_of(const Vec3<R>* r) {
    return dihedral_angle(r[1] - r[0], r[2] - r[1], r[3] - r[2]);
}

// Forces -dU/dphi grad(phi) on the four particles of a dihedral.
template <class R>
SMD_HD SMD_INLINE void write_dihedral_forces(const DihedralAngle<R>& angle, R dudphi, Vec3<R>* force) {
    for (int k = 0; k < 4; ++k) force[k] = (-dudphi) * angle.dphi_dr[k];
}

}  // namespace bonded_geometry
}  // namespace structmd
