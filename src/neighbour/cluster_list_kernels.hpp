#pragma once
// Functors of the cluster-pair list build (cluster_view.hpp), run after the Verlet list's counting
// sort of the particles by cell, under the same device-side rebuild flag: each cell's members put
// in Morton order of its sub-cells and cut into clusters, then each cluster's partners listed.
#include <cstdint>

#include "core/atomic.hpp"
#include "neighbour/cluster_view.hpp"
#include "neighbour/verlet_list_kernels.hpp"

namespace structmd {

// The Morton code of the sub-cell (4 x 4 x 4 to a cell) that holds r, in the cell (cx, cy, cz).
template <class R>
SMD_HD SMD_INLINE uint32_t sub_cell_code(const CellGrid<R>& grid, const Box<R>& box, Vec3<R> r, int cx, int cy,
                                         int cz) {
    const auto sub = [](R scaled, int cell) {
        const int s = static_cast<int>(floor((scaled - R(cell)) * R(4)));
        return static_cast<uint32_t>(s < 0 ? 0 : (s > 3 ? 3 : s));
    };
    const Vec3<R> u = grid.scaled(r, box);
    const uint32_t x = sub(u.x, cx);
    const uint32_t y = sub(u.y, cy);
    const uint32_t z = sub(u.z, cz);
    const auto spread = [](uint32_t v) { return (v & 1u) | ((v & 2u) << 2); };
    return spread(x) | spread(y) << 1 | spread(z) << 2;
}

// SortCells for a list with clusters: each cell's range ordered by (sub-cell code, particle), so the
// order still does not depend on thread timing and consecutive slots are close in space; then the
// positions copied and slots noted as SortCells does, and the cell cut into clusters with their
// bounding boxes (centre and half extent, by cluster id).
template <class R>
struct SortCellsIntoClusters {
    static constexpr int kSortable = 64;  // a more crowded cell keeps particle order (a collapsed system)
    const Real4<R>* pos;
    const int* control;
    const int* cellStart;
    CellGrid<R> grid;
    Box<R> box;
    int* order;
    int* slotOf;
    Real4<R>* positions;
    Real4<R>* binned;
    int* bounds;
    int* cellOfCluster;
    Real4<R>* centre;
    Real4<R>* halfExtent;

    SMD_HD void operator()(int64_t c) const {
        if (!control[kRebuild]) return;
        const int first = cellStart[c], members = cellStart[c + 1] - first;
        if (members <= kSortable) {
            int cx, cy, cz;
            grid.coordinates_of(static_cast<int>(c), cx, cy, cz);
            uint64_t key[kSortable];
            for (int m = 0; m < members; ++m) {
                const int i = order[first + m];
                key[m] = static_cast<uint64_t>(sub_cell_code(grid, box, xyz(pos[i]), cx, cy, cz)) << 32 |
                         static_cast<uint32_t>(i);
            }
            for (int m = 1; m < members; ++m) {
                const uint64_t v = key[m];
                int before = m - 1;
                while (before >= 0 && key[before] > v) {
                    key[before + 1] = key[before];
                    --before;
                }
                key[before + 1] = v;
            }
            for (int m = 0; m < members; ++m) order[first + m] = static_cast<int>(static_cast<uint32_t>(key[m]));
        } else {
            heap_sort(order + first, members);
        }
        for (int s = first; s < first + members; ++s) {
            const Real4<R> p = pos[order[s]];
            positions[s] = p;
            binned[s] = p;
            slotOf[order[s]] = s;
        }
        const int firstCluster = first / kClusterSize + static_cast<int>(c);
        const int nextCellFirstCluster = cellStart[c + 1] / kClusterSize + static_cast<int>(c) + 1;
        for (int id = firstCluster; id < nextCellFirstCluster; ++id) {
            const int begin = first + (id - firstCluster) * kClusterSize;
            const int end = begin + kClusterSize < first + members ? begin + kClusterSize : first + members;
            cellOfCluster[id] = static_cast<int>(c);
            bounds[2 * id] = begin < end ? begin : 0;
            bounds[2 * id + 1] = begin < end ? end : 0;
            if (begin >= end) continue;
            Vec3<R> low = xyz(binned[begin]), high = low;
            for (int s = begin + 1; s < end; ++s) {
                const Vec3<R> r = xyz(binned[s]);
                low = {r.x < low.x ? r.x : low.x, r.y < low.y ? r.y : low.y, r.z < low.z ? r.z : low.z};
                high = {r.x > high.x ? r.x : high.x, r.y > high.y ? r.y : high.y, r.z > high.z ? r.z : high.z};
            }
            centre[id] = {R(0.5) * (low.x + high.x), R(0.5) * (low.y + high.y), R(0.5) * (low.z + high.z), R(0)};
            halfExtent[id] = {R(0.5) * (high.x - low.x), R(0.5) * (high.y - low.y), R(0.5) * (high.z - low.z), R(0)};
        }
    }
};

// Each cluster's lanes take the clusters of the adjacent cells in rounds and append, in lane order,
// those with a particle within the list radius of one of the cluster's own: every pair within the
// list radius at the build is in some listed cluster pair. A bounding box out of reach rejects a
// candidate before its pairs are tried: a box of 4 particles reaches about three times as many
// clusters as its particles do, and each listed cluster costs 16 pair evaluations a step.
template <class R>
struct BuildClusterPairs {
    ClusterView<R> view;
    const Real4<R>* centre;
    const Real4<R>* halfExtent;
    R listRadius2;
    int* control;
    int* list;
    int* count;

    SMD_HD SMD_INLINE bool any_pair_within(int i, int j) const {
        const ClusterView<R>& v = view;
        for (int s = v.bounds[2 * i]; s < v.bounds[2 * i + 1]; ++s)
            for (int t = v.bounds[2 * j]; t < v.bounds[2 * j + 1]; ++t) {
                const Vec3<R> d = v.box.minimum_image(xyz(v.positions[t]) - xyz(v.positions[s]));
                if (dot(d, d) < listRadius2) return true;
            }
        return false;
    }

    SMD_HD void operator()(int64_t c, Lanes lanes) const {
        if (!control[kRebuild]) return;
        const ClusterView<R>& v = view;
        const int id = static_cast<int>(c);
        if (v.bounds[2 * id] == v.bounds[2 * id + 1]) {
            if (lanes.leader()) count[id] = 0;
            return;
        }
        const Vec3<R> ci = xyz(centre[id]), hi = xyz(halfExtent[id]);
        int* entries = list + static_cast<int64_t>(id) * v.capacity;
        int n = 0;
        const int cell = v.cellOf[id];
        const int cx = cell % v.grid.nx, cy = (cell / v.grid.nx) % v.grid.ny, cz = cell / (v.grid.nx * v.grid.ny);
        v.grid.for_each_adjacent(cx, cy, cz, 0, [&](int adjacent) {
            const int first = v.first_cluster(adjacent);
            const int end = first + (v.cellStart[adjacent + 1] - v.cellStart[adjacent] + kClusterSize - 1) / kClusterSize;
            for (int base = first; base < end; base += lanes.count) {
                const int j = base + lanes.lane;
                bool accepted = false;
                if (j < end) {
                    const Vec3<R> d = v.box.minimum_image(xyz(centre[j]) - ci);
                    const Vec3<R> reach = hi + xyz(halfExtent[j]);
                    const auto gap = [](R along, R within) {
                        const R g = (along < R(0) ? -along : along) - within;
                        return g > R(0) ? g : R(0);
                    };
                    const Vec3<R> g{gap(d.x, reach.x), gap(d.y, reach.y), gap(d.z, reach.z)};
                    accepted = dot(g, g) < listRadius2 && any_pair_within(id, j);
                }
                int found = 0;
                const int slot = n + lanes.rank_among(accepted, found);
                if (accepted && slot < v.capacity) entries[slot] = partner_entry(v.bounds[2 * j], v.bounds[2 * j + 1] - v.bounds[2 * j]);
                n += found;
            }
        });
        if (!lanes.leader()) return;
        count[id] = n;
        atomic_max(control + kMaxPartnerClusters, n);
    }
};

}  // namespace structmd
