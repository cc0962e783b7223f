#pragma once
// Orthorhombic periodic box spanning [-L/2, L/2) in each direction.
#include <cmath>

#include "core/vec.hpp"

namespace structmd {

template <class R>
struct Box {
    Vec3<R> length;
    Vec3<R> inverse;  // 1 / length, so that wrapping needs no division

    static Box make(double lx, double ly, double lz) {
        return {{R(lx), R(ly), R(lz)}, {R(1.0 / lx), R(1.0 / ly), R(1.0 / lz)}};
    }

    // The image of d closest to the origin, for d the difference of two wrapped positions (so
    // |d| < L along each axis): one compare per axis instead of a rounding call.
    SMD_HD SMD_INLINE Vec3<R> minimum_image(Vec3<R> d) const {
        d.x = fold(d.x, length.x);
        d.y = fold(d.y, length.y);
        d.z = fold(d.z, length.z);
        return d;
    }

    // Position folded into [-L/2, L/2).
    SMD_HD SMD_INLINE Vec3<R> wrap(Vec3<R> r) const {
        r.x -= length.x * floor(r.x * inverse.x + R(0.5));
        r.y -= length.y * floor(r.y * inverse.y + R(0.5));
        r.z -= length.z * floor(r.z * inverse.z + R(0.5));
        // Rounding can land exactly on +L/2; fold it back so the interval stays half-open.
        if (r.x >= R(0.5) * length.x) r.x -= length.x;
        if (r.y >= R(0.5) * length.y) r.y -= length.y;
        if (r.z >= R(0.5) * length.z) r.z -= length.z;
        return r;
    }

    static SMD_HD SMD_INLINE R fold(R d, R length) {
        if (d >= R(0.5) * length) return d - length;
        if (d < R(-0.5) * length) return d + length;
        return d;
    }

    R volume() const { return length.x * length.y * length.z; }
};

}  // namespace structmd
