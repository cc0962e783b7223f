#pragma once
// A particle's magnetic moment in the lab frame, mu = M R(q) m: the state's magnetization holds the
// unit direction m in the body frame (xyz) and the magnitude M (w), UAMMD-structured's layout, so a
// rigid dipole turns with its particle. Shared by the magnetic terms, integrators and getters.
#include "core/hd.hpp"
#include "core/quaternion.hpp"
#include "core/vec.hpp"

namespace structmd {

// dir: the orientations, or null when every particle is at the identity.
template <class R>
SMD_HD SMD_INLINE Vec3<R> to_lab_frame(const Real4<R>* dir, int64_t i, const Vec3<R>& body) {
    if (!dir) return body;
    const Real4<R> q = dir[i];
    return body.x * body_x(q) + body.y * body_y(q) + body.z * body_z(q);
}

// The inverse turn, R(q)^T v: a lab-frame vector in the body frame.
template <class R>
SMD_HD SMD_INLINE Vec3<R> to_body_frame(const Real4<R>* dir, int64_t i, const Vec3<R>& lab) {
    if (!dir) return lab;
    const Real4<R> q = dir[i];
    return {dot(lab, body_x(q)), dot(lab, body_y(q)), dot(lab, body_z(q))};
}

template <class R>
SMD_HD SMD_INLINE Vec3<R> magnetic_moment(const Real4<R>* magnetization, const Real4<R>* dir, int64_t i) {
    const Real4<R> m = magnetization[i];
    return m.w * to_lab_frame(dir, i, Vec3<R>{m.x, m.y, m.z});
}

}  // namespace structmd
