#pragma once
// The spreading S and the average J = S^T of the doubly periodic slab (slab_mesh.hpp) from weights
// tabulated once per placement. A particle's Gaussian is a product of one weight per axis (x and y
// periodic, z bounded and with the walls' images), so SlabWeighParticle stores each group member's
// first grid point and its support weights along x and y and supportZ along z; the products that
// follow (several a step: the deterministic one, the Lanczos iteration's, the random finite
// difference's) read them instead of evaluating some 2 support^2 supportZ exponentials per particle
// each time.
//
// The spreading is one grid line along x per item, as gaussian_spreading.hpp's GaussianSpreadLine
// (which the force coupling method shares): the particles sorted by the line their Gaussian starts
// on (LineBins, keyed by SlabKernelLine), each line summing the bins its Gaussian reaches in a fixed
// order, its lanes owning the points x modulo their count, so no atomics and the same sum on any
// number of lanes. The average is one particle per item, its lanes sharing out the grid lines the
// Gaussian covers and adding their sums in a fixed butterfly.
#include <cstdint>

#include "core/fft_grid.hpp"
#include "core/hd.hpp"
#include "core/lanes.hpp"
#include "core/vec.hpp"
#include "hydrodynamics/gaussian_spreading.hpp"

namespace structmd {

// i modulo n in [0, n), for i > -n.
SMD_HD SMD_INLINE int slab_fold(int i, int n) { return i < 0 ? i + n : (i >= n ? i - n : i); }

// The tabulated weights, read side: particle i's first grid point along x and y (folded into the
// grid) and z at first[3 i ..], and its weights at weight[stride() i ..]: x's `support`, y's
// `support`, z's `supportZ`. Group members only.
template <class R>
struct SlabWeights {
    const int* first;
    const R* weight;
    int support, supportZ;

    SMD_HD SMD_INLINE int stride() const { return 2 * support + supportZ; }
    SMD_HD SMD_INLINE int first_x(int64_t i) const { return first[3 * i]; }
    SMD_HD SMD_INLINE int first_y(int64_t i) const { return first[3 * i + 1]; }
    SMD_HD SMD_INLINE int first_z(int64_t i) const { return first[3 * i + 2]; }
    SMD_HD SMD_INLINE R x(int64_t i, int a) const { return weight[stride() * i + a]; }
    SMD_HD SMD_INLINE R y(int64_t i, int b) const { return weight[stride() * i + support + b]; }
    SMD_HD SMD_INLINE R z(int64_t i, int c) const { return weight[stride() * i + 2 * support + c]; }
};

// Tabulates group member i's first points and weights (the layout of SlabWeights) for the axes:
// x and y periodic (FcmAxis), z the slab's (AxisZ: first(z), weight(node, z)).
template <class R, class AxisZ>
struct SlabWeighParticle {
    const Real4<R>* pos;
    const uint8_t* group;
    GaussianAxes<R, AxisZ> axes;
    int* first;
    R* weight;

    SMD_HD void operator()(int64_t i) const {
        if (group && !group[i]) return;
        const Real4<R> r = pos[i];
        const R ux = axes.x.coordinate(r.x), uy = axes.y.coordinate(r.y);
        const int firstX = axes.x.first(ux), firstY = axes.y.first(uy), firstZ = axes.z.first(r.z);
        first[3 * i] = axes.x.fold(firstX);
        first[3 * i + 1] = axes.y.fold(firstY);
        first[3 * i + 2] = firstZ;
        const int support = axes.x.support;
        R* w = weight + int64_t(2 * support + axes.z.support) * i;
        for (int a = 0; a < support; ++a) w[a] = axes.x.weight(firstX, a, ux);
        for (int b = 0; b < support; ++b) w[support + b] = axes.y.weight(firstY, b, uy);
        for (int c = 0; c < axes.z.support; ++c) w[2 * support + c] = axes.z.weight(firstZ + c, r.z);
    }
};

// The grid line (y, z) a group member's Gaussian starts on, by which LineBins sorts the particles
// (-1: not a member, it spreads nothing).
struct SlabKernelLine {
    const uint8_t* group;
    const int* first;  // SlabWeights'
    int ny;
    SMD_HD int operator()(int64_t i) const {
        if (group && !group[i]) return -1;
        return first[3 * i + 2] * ny + first[3 * i + 1];
    }
};

// One grid line along x of the three density grids (x, y, z components, one after the other),
// cleared and then summed: a particle whose Gaussian starts on line (y - b, z - c) adds
// v w_x w_y[b] w_z[c] along the line. Bins in (c, b) order and each in particle order. The lanes
// read the bounds of up to `count` bins of a row at once instead of one bin after the other.
template <class R, class Vectors>
struct SlabSpreadLine {
    Vectors vectors;
    const int* order;
    const int* lineStart;
    SlabWeights<R> weights;
    FftGrid grid;
    R* density;

    SMD_HD void operator()(int64_t line, Lanes lanes) const {
        const int y = static_cast<int>(line % grid.ny), z = static_cast<int>(line / grid.ny);
        const DensityLine<R> row(density, grid, y, z, lanes);
        const int support = weights.support;
        for (int c = 0; c < weights.supportZ && c <= z; ++c) {
            const int binRow = (z - c) * grid.ny;
            for (int firstB = 0; firstB < support; firstB += lanes.count) {
                int begin = 0, end = 0;
                if (firstB + lanes.lane < support) {
                    const int bin = binRow + slab_fold(y - firstB - lanes.lane, grid.ny);
                    begin = lineStart[bin];
                    end = lineStart[bin + 1];
                }
                const int lastB = firstB + lanes.count < support ? firstB + lanes.count : support;
                for (int b = firstB; b < lastB; ++b) {
                    const int first = lanes.from_lane(begin, b - firstB), last = lanes.from_lane(end, b - firstB);
                    for (int s = first; s < last; ++s) {
                        const int i = order[s];
                        const R wyz = weights.y(i, b) * weights.z(i, c);
                        const Vec3<R> v = vectors[i];
                        int at = weights.first_x(i);
                        for (int a = 0; a < support; ++a, at = at + 1 == grid.nx ? 0 : at + 1) {
                            if (!owns_point(lanes, at)) continue;
                            row.add(at, wyz * weights.x(i, a), v);
                        }
                    }
                }
            }
        }
    }
};

// Each group member's vector (flat: 3i, 3i+1, 3i+2): the grid's field (three grids, x, y, z
// components) averaged by its Gaussian, times the cell volume; 0 for the others. The lanes take
// the Gaussian's grid lines (y, z) in turn, each summing along x.
template <class R>
struct SlabInterpolate {
    const uint8_t* group;
    SlabWeights<R> weights;
    FftGrid grid;
    const R* field;
    R cellVolume;
    R* out;

    SMD_HD void operator()(int64_t i, Lanes lanes) const {
        Vec3<R> sum{R(0), R(0), R(0)};
        if (!group || group[i]) {
            const int64_t points = grid.points();
            const int support = weights.support, lines = support * weights.supportZ;
            const int firstX = weights.first_x(i), firstY = weights.first_y(i), firstZ = weights.first_z(i);
            for (int line = lanes.lane; line < lines; line += lanes.count) {
                const int c = line / support, b = line - c * support;
                const R wyz = weights.z(i, c) * weights.y(i, b);
                const R* row = field + grid.index(0, slab_fold(firstY + b, grid.ny), firstZ + c);
                int at = firstX;
                for (int a = 0; a < support; ++a, at = at + 1 == grid.nx ? 0 : at + 1) {
                    const R w = wyz * weights.x(i, a);
                    sum.x += w * row[at];
                    sum.y += w * row[at + points];
                    sum.z += w * row[at + 2 * points];
                }
            }
            sum = lanes.sum(sum);
        }
        if (!lanes.leader()) return;
        out[3 * i] = cellVolume * sum.x;
        out[3 * i + 1] = cellVolume * sum.y;
        out[3 * i + 2] = cellVolume * sum.z;
    }
};

}  // namespace structmd
