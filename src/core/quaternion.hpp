#pragma once
// Orientations as unit quaternions q = (q0; q1, q2, q3), stored in a Real4 as UAMMD-structured does:
// x = q0 (the scalar part), y, z, w = q1, q2, q3. The body frame's axes in the lab frame are the
// columns of the rotation matrix R(q).
#include <cmath>

#include "core/hd.hpp"
#include "core/vec.hpp"

namespace structmd {

// q after a rotation by the lab-frame rotation vector theta (angle |theta| about theta / |theta|):
// exp(theta / 2) q, the exact exponential, renormalised so that rounding never lets |q| drift.
template <class R>
SMD_HD SMD_INLINE Real4<R> rotated(const Real4<R>& q, const Vec3<R>& theta) {
    const R angle = sqrt(dot(theta, theta));
    const R half = R(0.5) * angle;
    // sin(half) / angle, with its limit 1/2 for a vanishing angle.
    const R s = angle > R(1e-12) ? sin(half) / angle : R(0.5);
    const R a = cos(half), b = s * theta.x, c = s * theta.y, d = s * theta.z;
    // (a; b, c, d) * (q0; q1, q2, q3)
    Real4<R> r{a * q.x - b * q.y - c * q.z - d * q.w, a * q.y + b * q.x + c * q.w - d * q.z,
               a * q.z - b * q.w + c * q.x + d * q.y, a * q.w + b * q.z - c * q.y + d * q.x};
    const R inverseNorm = R(1) / sqrt(r.x * r.x + r.y * r.y + r.z * r.z + r.w * r.w);
    r.x *= inverseNorm;
    r.y *= inverseNorm;
    r.z *= inverseNorm;
    r.w *= inverseNorm;
    return r;
}

// The body frame's x, y and z axes in the lab frame (the columns of R(q)).
template <class R>
SMD_HD SMD_INLINE Vec3<R> body_x(const Real4<R>& q) {
    return {R(1) - R(2) * (q.z * q.z + q.w * q.w), R(2) * (q.y * q.z + q.x * q.w), R(2) * (q.y * q.w - q.x * q.z)};
}
template <class R>
SMD_HD SMD_INLINE Vec3<R> body_y(const Real4<R>& q) {
    return {R(2) * (q.y * q.z - q.x * q.w), R(1) - R(2) * (q.y * q.y + q.w * q.w), R(2) * (q.z * q.w + q.x * q.y)};
}
template <class R>
SMD_HD SMD_INLINE Vec3<R> body_z(const Real4<R>& q) {
    return {R(2) * (q.y * q.w + q.x * q.z), R(2) * (q.z * q.w - q.x * q.y), R(1) - R(2) * (q.y * q.y + q.z * q.z)};
}

}  // namespace structmd
