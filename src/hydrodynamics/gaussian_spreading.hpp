#pragma once
// Spreading particles' vectors onto a 3D grid with a Gaussian, and averaging a grid's field back at
// the particles with the same Gaussian (S and J = S^T of the grid methods for hydrodynamics): the
// force coupling method and the positively split Ewald far field (fcm_mesh.hpp, periodic along z).
// The Gaussian is a product of one weight per axis; x and y are periodic (FcmAxis), z is the
// method's (here FcmAxis, answering first_node, node_weight, plane and plane_below). The doubly
// periodic slab (slab_mesh.hpp, bounded along z: SlabAxisZ) tabulates the same axes' weights once
// per placement and spreads them with its own functors (slab_spreading.hpp).
//
// Vectors go onto the grid one line along x per item (up to a warp on the GPU, each lane summing the
// points it owns: core/lanes.hpp's owns_point) from the particles sorted by the line their kernel
// starts on (neighbour/line_bins.hpp, as the particle-mesh Ewald of electrostatics does).
#include <cmath>
#include <cstdint>

#include "core/fft_grid.hpp"
#include "core/hd.hpp"
#include "core/lanes.hpp"
#include "core/vec.hpp"

namespace structmd {

// The Gaussian's weights along one periodic axis: a particle at grid coordinate u reaches the
// `support` points first .. first + support - 1 (not folded), the ones closest to it.
template <class R>
struct FcmAxis {
    R spacing;        // h = L / n
    R inverseLength;  // 1 / L
    int n;
    int support;
    R inverseTwoSigma2;  // 1 / (2 sigma^2)
    R norm;              // (2 pi sigma^2)^{-1/2}

    SMD_HD SMD_INLINE R coordinate(R x) const { return R(n) * (x * inverseLength + R(0.5)); }
    SMD_HD SMD_INLINE int first(R u) const { return static_cast<int>(floor(u - R(0.5) * R(support) + R(1))); }
    // The weight at point first + j (distance (first + j - u) h).
    SMD_HD SMD_INLINE R weight(int first, int j, R u) const {
        const R d = (R(first + j) - u) * spacing;
        return norm * exp(-d * d * inverseTwoSigma2);
    }
    SMD_HD SMD_INLINE int fold(int i) const {
        const int m = i % n;
        return m < 0 ? m + n : m;
    }

    // As the z axis: the first node a particle at z reaches (not folded), the weight at node
    // first + c, the plane of node i, and the plane where the kernels start that reach `plane` from
    // c planes below (negative: none).
    SMD_HD SMD_INLINE int first_node(R z) const { return first(coordinate(z)); }
    SMD_HD SMD_INLINE R node_weight(int firstNode, int c, R z) const { return weight(firstNode, c, coordinate(z)); }
    SMD_HD SMD_INLINE int plane(int i) const { return fold(i); }
    SMD_HD SMD_INLINE int plane_below(int plane, int c) const { return fold(plane - c); }
};

template <class R, class AxisZ>
struct GaussianAxes {
    FcmAxis<R> x, y;
    AxisZ z;
    FftGrid grid;
};

// The vector particle i spreads: its force, or three numbers of a flat array.
template <class R>
struct Real4Vectors {
    const Real4<R>* v;
    SMD_HD SMD_INLINE Vec3<R> operator[](int i) const {
        const Real4<R> f = v[i];
        return {f.x, f.y, f.z};
    }
};
template <class R>
struct FlatVectors {
    const R* v;
    SMD_HD SMD_INLINE Vec3<R> operator[](int i) const { return {v[3 * i], v[3 * i + 1], v[3 * i + 2]}; }
};

// The grid line (y, z) a group member's kernel starts on, by which LineBins sorts the particles.
template <class R, class AxisZ>
struct GaussianKernelLine {
    const Real4<R>* pos;
    const uint8_t* group;
    GaussianAxes<R, AxisZ> axes;
    SMD_HD int operator()(int64_t i) const {
        if (group && !group[i]) return -1;
        const Real4<R> r = pos[i];
        const int y = axes.y.fold(axes.y.first(axes.y.coordinate(r.y)));
        return axes.z.plane(axes.z.first_node(r.z)) * axes.grid.ny + y;
    }
};

// The x, y and z rows of grid line (y, z) along x in a density of three grids one after the other
// (x, y, z components), with the points each lane owns cleared (owns_point: x modulo the lane count).
template <class R>
struct DensityLine {
    R* x;
    R* y;
    R* z;

    SMD_HD SMD_INLINE DensityLine(R* density, const FftGrid& grid, int lineY, int lineZ, const Lanes& lanes)
        : x(density + grid.index(0, lineY, lineZ)), y(x + grid.points()), z(y + grid.points()) {
        for (int at = lanes.lane; at < grid.nx; at += lanes.count) x[at] = y[at] = z[at] = R(0);
    }

    // Adds w v at point `at`.
    SMD_HD SMD_INLINE void add(int at, R w, const Vec3<R>& v) const {
        x[at] += w * v.x;
        y[at] += w * v.y;
        z[at] += w * v.z;
    }
};

// One grid line along x of the three density grids (x, y, z components, one after the other),
// cleared and then summed: a particle whose kernel starts on line (y - b, z - c) adds
// v g_x g_y[b] g_z[c] along the line. Bins in (c, b) order and each in particle order.
// Every lane computes each particle's y and z weights (two exps) and sums only its own points, the
// same terms in the same order on any power-of-two number of lanes: launched with
// LaneSizing::kFillDevice, so a line gets lanes only until the lines fill the device (32 lanes
// repeated those weights and cost 3-5% at 100,000 particles, where the lines alone fill it).
template <class R, class AxisZ, class Vectors>
struct GaussianSpreadLine {
    const Real4<R>* pos;
    Vectors vectors;
    const int* order;
    const int* lineStart;
    GaussianAxes<R, AxisZ> axes;
    R* density;

    SMD_HD void operator()(int64_t line, Lanes lanes) const {
        const FftGrid& g = axes.grid;
        const int y = static_cast<int>(line % g.ny), z = static_cast<int>(line / g.ny);
        const DensityLine<R> row(density, g, y, z, lanes);
        const int support = axes.x.support;
        for (int c = 0; c < axes.z.support; ++c) {
            const int binZ = axes.z.plane_below(z, c);
            if (binZ < 0) break;
            for (int b = 0; b < support; ++b) {
                const int bin = binZ * g.ny + axes.y.fold(y - b);
                for (int s = lineStart[bin]; s < lineStart[bin + 1]; ++s) {
                    const int i = order[s];
                    const Real4<R> r = pos[i];
                    const R uy = axes.y.coordinate(r.y);
                    const R wyz = axes.y.weight(axes.y.first(uy), b, uy) * axes.z.node_weight(axes.z.first_node(r.z), c, r.z);
                    const Vec3<R> v = vectors[i];
                    const R ux = axes.x.coordinate(r.x);
                    const int firstX = axes.x.first(ux);
                    for (int a = 0; a < support; ++a) {
                        const int at = axes.x.fold(firstX + a);
                        if (!owns_point(lanes, at)) continue;
                        row.add(at, wyz * axes.x.weight(firstX, a, ux), v);
                    }
                }
            }
        }
    }
};

// Each group member's vector (flat: 3i, 3i+1, 3i+2): the grid's field (three grids, x, y, z
// components) averaged by its Gaussian, times the cell volume; 0 for the others.
template <class R, class AxisZ>
struct GaussianInterpolate {
    const Real4<R>* pos;
    const uint8_t* group;
    GaussianAxes<R, AxisZ> axes;
    const R* field;
    R cellVolume;
    R* out;

    SMD_HD void operator()(int64_t i) const {
        Vec3<R> sum{R(0), R(0), R(0)};
        if (!group || group[i]) {
            const FftGrid& g = axes.grid;
            const int64_t points = g.points();
            const Real4<R> r = pos[i];
            const R ux = axes.x.coordinate(r.x), uy = axes.y.coordinate(r.y);
            const int firstX = axes.x.first(ux), firstY = axes.y.first(uy), firstZ = axes.z.first_node(r.z);
            const int support = axes.x.support;
            for (int c = 0; c < axes.z.support; ++c) {
                const R wz = axes.z.node_weight(firstZ, c, r.z);
                for (int b = 0; b < support; ++b) {
                    const R wyz = wz * axes.y.weight(firstY, b, uy);
                    const R* line = field + g.index(0, axes.y.fold(firstY + b), axes.z.plane(firstZ + c));
                    for (int a = 0; a < support; ++a) {
                        const int at = axes.x.fold(firstX + a);
                        const R w = wyz * axes.x.weight(firstX, a, ux);
                        sum.x += w * line[at];
                        sum.y += w * line[at + points];
                        sum.z += w * line[at + 2 * points];
                    }
                }
            }
        }
        out[3 * i] = cellVolume * sum.x;
        out[3 * i + 1] = cellVolume * sum.y;
        out[3 * i + 2] = cellVolume * sum.z;
    }
};

}  // namespace structmd
