#pragma once
// The 3N x 3N mobility of N spheres in an unbounded fluid, made of RPY pair blocks (rpy_tensor.hpp),
// over the spheres as the hydrodynamics sees them: each particle's unwrapped centre and hydrodynamic
// radius, radius 0 marking a particle that takes no part (outside the integrator's group). Such a
// particle neither moves nor disturbs the flow: its rows and columns of M are zero, or the identity
// where a factorisation needs the matrix positive definite.
// All vectors are flat arrays of 3N numbers, particle i's components at 3i, 3i+1, 3i+2.
#include <cstdint>

#include "core/box.hpp"
#include "core/lanes.hpp"
#include "core/vec.hpp"
#include "hydrodynamics/rpy_tensor.hpp"

namespace structmd {

// The spheres from the particles: positions unwrapped by their box crossings, because the fluid
// has no periodic images; the radius is the integrator's hydrodynamic radius, or each particle's own
// where that is 0.
template <class R>
struct PlaceSpheres {
    Real4<R>* spheres;  // xyz: centre, w: radius (0: not in the group)
    const Real4<R>* pos;
    const Image* image;
    const R* radius;
    const uint8_t* group;
    Box<R> box;
    R hydrodynamicRadius;
    SMD_HD void operator()(int64_t i) const {
        const Real4<R> p = pos[i];
        const Image n = image[i];
        const bool member = !group || group[i];
        spheres[i] = {p.x + Box<R>::image_offset(n.x, box.length.x), p.y + Box<R>::image_offset(n.y, box.length.y),
                      p.z + Box<R>::image_offset(n.z, box.length.z),
                      member ? (hydrodynamicRadius > R(0) ? hydrodynamicRadius : radius[i]) : R(0)};
    }
};

// out = M v, one particle's three rows per item: an O(N^2) pair sum, split over the item's lanes
// so that a thousand particles still fill the device.
template <class R>
struct MobilityProduct {
    const Real4<R>* spheres;
    int64_t count;
    RpyTensor<R> rpy;
    const R* v;
    R* out;
    SMD_HD void operator()(int64_t i, Lanes lanes) const {
        const Real4<R> si = spheres[i];
        Vec3<R> sum{R(0), R(0), R(0)};
        if (si.w > R(0))
            for (int64_t j = lanes.lane; j < count; j += lanes.count) {
                const Real4<R> sj = spheres[j];
                if (!(sj.w > R(0))) continue;
                const Vec3<R> d{sj.x - si.x, sj.y - si.y, sj.z - si.z};
                sum += rpy.apply(d, si.w, sj.w, Vec3<R>{v[3 * j], v[3 * j + 1], v[3 * j + 2]});
            }
        sum = lanes.sum(sum);
        if (!lanes.leader()) return;
        out[3 * i] = sum.x;
        out[3 * i + 1] = sum.y;
        out[3 * i + 2] = sum.z;
    }
};

// The dense M, column-major with leading dimension 3N, one 3 x 3 block (i, j) per call for
// k = i + N j. A particle outside the group has the identity as its diagonal block (any positive
// value keeps M factorisable; nothing reads its noise).
template <class R>
struct FillDenseMobility {
    const Real4<R>* spheres;
    int64_t count;
    RpyTensor<R> rpy;
    R* matrix;
    SMD_HD void operator()(int64_t k) const {
        const int64_t i = k % count, j = k / count;
        const Real4<R> si = spheres[i], sj = spheres[j];
        const bool coupled = si.w > R(0) && sj.w > R(0);
        const Vec3<R> d{sj.x - si.x, sj.y - si.y, sj.z - si.z};
        const int64_t rows = 3 * count;
        for (int b = 0; b < 3; ++b)
            for (int a = 0; a < 3; ++a) {
                R value = R(0);
                if (coupled) value = rpy.entry(d, si.w, sj.w, a, b);
                else if (i == j && a == b) value = R(1);
                matrix[(3 * i + a) + (3 * j + b) * rows] = value;
            }
    }
};

}  // namespace structmd
