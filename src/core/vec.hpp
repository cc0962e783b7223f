#pragma once
// Small vector and tensor types shared by host and device code.
#include "core/hd.hpp"
#if SMD_HOST_CODE
#include <cmath>
#endif

namespace structmd {

template <class R>
struct Vec3 {
    R x, y, z;
};

// Particle record of four reals: positions keep the type index in w, velocities the mass, so that
// a kernel gets both with one aligned load.
template <class R>
struct alignas(4 * sizeof(R)) Real4 {
    R x, y, z, w;
};

// Row-major 3x3 tensor (virial).
template <class R>
struct Tensor3 {
    R xx, xy, xz, yx, yy, yz, zx, zy, zz;
};

template <class R> SMD_HD SMD_INLINE Vec3<R> operator+(Vec3<R> a, Vec3<R> b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
template <class R> SMD_HD SMD_INLINE Vec3<R> operator-(Vec3<R> a, Vec3<R> b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <class R> SMD_HD SMD_INLINE Vec3<R> operator-(Vec3<R> a) { return {-a.x, -a.y, -a.z}; }
template <class R> SMD_HD SMD_INLINE Vec3<R> operator*(R s, Vec3<R> a) { return {s * a.x, s * a.y, s * a.z}; }
template <class R> SMD_HD SMD_INLINE Vec3<R>& operator+=(Vec3<R>& a, Vec3<R> b) { a.x += b.x; a.y += b.y; a.z += b.z; return a; }
template <class R> SMD_HD SMD_INLINE Vec3<R>& operator-=(Vec3<R>& a, Vec3<R> b) { a.x -= b.x; a.y -= b.y; a.z -= b.z; return a; }
template <class R> SMD_HD SMD_INLINE R dot(Vec3<R> a, Vec3<R> b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <class R> SMD_HD SMD_INLINE Vec3<R> xyz(Real4<R> a) { return {a.x, a.y, a.z}; }

template <class R> SMD_HD SMD_INLINE Tensor3<R> outer(Vec3<R> a, Vec3<R> b) {
    return {a.x * b.x, a.x * b.y, a.x * b.z, a.y * b.x, a.y * b.y, a.y * b.z, a.z * b.x, a.z * b.y, a.z * b.z};
}
template <class R> SMD_HD SMD_INLINE Tensor3<R> zero_tensor() { return {0, 0, 0, 0, 0, 0, 0, 0, 0}; }
template <class R> SMD_HD SMD_INLINE Tensor3<R>& operator+=(Tensor3<R>& a, const Tensor3<R>& b) {
    a.xx += b.xx; a.xy += b.xy; a.xz += b.xz;
    a.yx += b.yx; a.yy += b.yy; a.yz += b.yz;
    a.zx += b.zx; a.zy += b.zy; a.zz += b.zz;
    return a;
}
template <class R> SMD_HD SMD_INLINE Tensor3<R> operator+(Tensor3<R> a, const Tensor3<R>& b) { return a += b; }
template <class R> SMD_HD SMD_INLINE Tensor3<R> operator*(R s, const Tensor3<R>& a) {
    return {s * a.xx, s * a.xy, s * a.xz, s * a.yx, s * a.yy, s * a.yz, s * a.zx, s * a.zy, s * a.zz};
}

}  // namespace structmd
