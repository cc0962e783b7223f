#pragma once
// What a pair kernel sees of a cluster-pair list: plain pointers, copied by value into the kernel.
//
// A cluster is up to kClusterSize consecutive slots of one cell of the Verlet list's grid (the cell's
// members ordered along a Morton curve of its sub-cells at the build, so a cluster is compact), and
// each cluster lists the clusters whose bounding boxes came within the list radius of its own at the
// build. A kernel then loads a partner cluster's few positions once for all the pairs of the two
// clusters, instead of one gathered position per pair, and reads one list entry per cluster instead
// of one per particle (in the spirit of GROMACS's cluster pairs, Pall and Hess 2013).
//
// Cell c owns the cluster ids first_cluster(c) .. first_cluster(c + 1) - 1, with first_cluster(c) =
// cellStart[c] / kClusterSize + c: enough ids for ceil(members / kClusterSize) clusters without a scan;
// the ids a cell does not fill are empty clusters (first slot == end slot). A list entry is the
// partner's first slot and size in one integer (partner_entry), so a kernel goes from the entry to the
// positions without a lookup. A cluster whose list overflowed its capacity is served by scanning the
// clusters of the adjacent cells, so the result never depends on a capacity guess.
#include "core/lanes.hpp"
#include "neighbour/cell_grid.hpp"

namespace structmd {

constexpr int kClusterSize = 4;

// A partner's slots first .. first + size - 1 (1 <= size <= 4) as one list entry, and back.
SMD_HD SMD_INLINE int partner_entry(int first, int size) { return first << 2 | (size - 1); }
SMD_HD SMD_INLINE int entry_first(int entry) { return entry >> 2; }
SMD_HD SMD_INLINE int entry_end(int entry) { return (entry >> 2) + (entry & 3) + 1; }

template <class R>
struct ClusterView {
    const Real4<R>* positions = nullptr;  // this step's positions, by slot
    const int* order = nullptr;           // the particle in each slot
    const int* bounds = nullptr;          // cluster c: slots bounds[2c] .. bounds[2c + 1] - 1
    const int* cellOf = nullptr;          // the cell each cluster belongs to
    const int* list = nullptr;            // partner m of cluster c at list[c * capacity + m] (partner_entry)
    const int* count = nullptr;
    int capacity = 0;
    int clusters = 0;                     // cluster ids, empty ones included
    const int* cellStart = nullptr;
    CellGrid<R> grid;
    Box<R> box;

    SMD_HD SMD_INLINE int first_cluster(int cell) const { return cellStart[cell] / kClusterSize + cell; }

    SMD_HD SMD_INLINE bool overflowed(int c) const { return count[c] > capacity; }
    SMD_HD SMD_INLINE const int* entries_of(int c) const { return list + static_cast<int64_t>(c) * capacity; }

    // visit(first, end) for the slots of each partner cluster of cluster c (c itself among them) in
    // stream `stream` of `streams` interleaved ones, in an order that does not depend on thread timing.
    template <class Visit>
    SMD_HD SMD_INLINE void for_each_partner(int c, int stream, int streams, Visit&& visit) const {
        const int n = count[c];
        if (n <= capacity) {
            const int* entries = entries_of(c);
            for (int m = stream; m < n; m += streams) visit(entry_first(entries[m]), entry_end(entries[m]));
            return;
        }
        int candidate = 0;
        for_each_adjacent_cluster(c, [&](int j) {
            if (candidate++ % streams == stream) visit(bounds[2 * j], bounds[2 * j + 1]);
        });
    }

    // Every non-empty cluster of the cells adjacent to cluster c's (its own included).
    template <class Visit>
    SMD_HD SMD_INLINE void for_each_adjacent_cluster(int c, Visit&& visit) const {
        const int cell = cellOf[c];
        const int cx = cell % grid.nx, cy = (cell / grid.nx) % grid.ny, cz = cell / (grid.nx * grid.ny);
        grid.for_each_adjacent(cx, cy, cz, 0, [&](int adjacent) {
            const int members = cellStart[adjacent + 1] - cellStart[adjacent];
            const int first = first_cluster(adjacent);
            for (int j = first; j < first + (members + kClusterSize - 1) / kClusterSize; ++j) visit(j);
        });
    }
};

}  // namespace structmd
