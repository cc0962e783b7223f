#pragma once
// Orthorhombic box spanning [-L/2, L/2) along each periodic axis. An axis of length infinity is open
// (not periodic, as UAMMD's Box takes a length of 0 or infinity): positions are never wrapped along it
// and the nearest image of a particle is the particle itself.
#include "core/real_limits.hpp"
#include "core/vec.hpp"

#if SMD_HOST_CODE
#include <algorithm>
#include <cmath>
#include <limits>
#endif

namespace structmd {

// The longest box edge accepted, from the input and from set_box alike: it keeps every count derived
// from the box (cells of a grid, images) finite.
#if SMD_HOST_CODE
inline constexpr double kLargestBoxLength = 1e15;

// The minimum-image rule: a cutoff (of a pair term, of a measure's neighbourhood) must be shorter than
// this, half the shortest edge, so that each pair is seen through one image only.
// (infinity in a box open along every axis, where any cutoff fits).
inline double half_shortest_edge(double lx, double ly, double lz) { return 0.5 * std::min({lx, ly, lz}); }

inline constexpr double kOpenAxis = std::numeric_limits<double>::infinity();

inline bool is_open_axis(double length) { return length == kOpenAxis; }

// A length the engine keeps for an axis: periodic (> 0, <= kLargestBoxLength) or open (infinity).
inline bool is_box_length(double length) {
    return is_open_axis(length) || (length > 0.0 && length <= kLargestBoxLength);
}

inline bool has_open_axis(double lx, double ly, double lz) {
    return is_open_axis(lx) || is_open_axis(ly) || is_open_axis(lz);
}
#endif

// How many box lengths a particle has crossed along each axis since its position was set.
struct Image {
    int x, y, z;
};

template <class R>
struct Box {
    Vec3<R> length;
    Vec3<R> inverse;  // 1 / length, so that wrapping needs no division

#if SMD_HOST_CODE
    // An open axis (length infinity) has an inverse of 0, so it never wraps.
    static Box make(double lx, double ly, double lz) {
        return {{R(lx), R(ly), R(lz)}, {R(1.0 / lx), R(1.0 / ly), R(1.0 / lz)}};
    }
#endif

    // What `image` box crossings add to a wrapped coordinate: 0 without crossings, also along an open
    // axis, where image times infinity would be NaN.
    static SMD_HD SMD_INLINE R image_offset(int image, R length) { return image == 0 ? R(0) : R(image) * length; }

    // The image of d closest to the origin, for d the difference of two wrapped positions (so
    // |d| < L along each axis): d less L times d / L rounded, -1, 0 or 1, the product exact, so d - L
    // or d + L rounded once, as a compare would choose, except that d exactly +-L/2 (within a rounding
    // of d / L) may fold either way; a cutoff is shorter. Four instructions an axis (a multiply, the
    // rounding's two additions, a fused multiply-add) where a compare and a select of each side took
    // six in a pair kernel's loop; its period, 0 along an open axis (whose d / L is 0, and L infinite),
    // is the same for every pair and leaves the loop.
    SMD_HD SMD_INLINE Vec3<R> minimum_image(Vec3<R> d) const {
        d.x = fold(d.x, inverse.x, period(length.x, inverse.x));
        d.y = fold(d.y, inverse.y, period(length.y, inverse.y));
        d.z = fold(d.z, inverse.z, period(length.z, inverse.z));
        return d;
    }

    // Position folded into [-L/2, L/2).
    SMD_HD SMD_INLINE Vec3<R> wrap(Vec3<R> r) const {
        Image image{0, 0, 0};
        return wrap(r, image);
    }

    // As wrap(r), adding to image the box lengths removed along each axis, so that the unwrapped
    // position is the wrapped one plus image times L.
    SMD_HD SMD_INLINE Vec3<R> wrap(Vec3<R> r, Image& image) const {
        r.x = wrap_axis(r.x, length.x, inverse.x, image.x);
        r.y = wrap_axis(r.y, length.y, inverse.y, image.y);
        r.z = wrap_axis(r.z, length.z, inverse.z, image.z);
        return r;
    }

    // Shifts beyond a billion box lengths are clamped (the conversion to int would overflow): such a
    // particle has blown up and the integrators report it; NaN stays NaN.
    static SMD_HD SMD_INLINE R wrap_axis(R x, R length, R inverse, int& image) {
        const R lengths = floor(x * inverse + R(0.5));
        int shift = lengths < R(1e9) ? (lengths > R(-1e9) ? static_cast<int>(lengths) : -1000000000) : 1000000000;
        if (lengths != lengths) shift = 0;
        // An open axis (inverse 0) gives no shift; its length, infinity, times 0 would be NaN.
        if (shift != 0) x -= length * R(shift);
        // Rounding can land exactly on +L/2; fold it back so the interval stays half-open.
        if (x >= R(0.5) * length) {
            x -= length;
            ++shift;
        }
        image = image_added(image, shift);
        return x;
    }

    // image + shift, saturated: a particle that blew up may wrap by a billion boxes step after step.
    static SMD_HD SMD_INLINE int image_added(int image, int shift) {
        const long long images = static_cast<long long>(image) + shift;
        return images > 2147483647LL ? 2147483647 : (images < -2147483647LL ? -2147483647 : static_cast<int>(images));
    }
    static SMD_HD SMD_INLINE Image images_added(const Image& image, const Image& shift) {
        return {image_added(image.x, shift.x), image_added(image.y, shift.y), image_added(image.z, shift.z)};
    }

    // No branch (nvcc made a compare's second side a branch and a reconvergence point in every loop
    // over neighbours).
    static SMD_HD SMD_INLINE R period(R length, R inverse) { return inverse == R(0) ? R(0) : length; }
    static SMD_HD SMD_INLINE R fold(R d, R inverse, R period) { return d - nearest_integer(d * inverse) * period; }
};

}  // namespace structmd
