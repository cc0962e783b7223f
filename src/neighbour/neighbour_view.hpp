#pragma once
// What a pair kernel sees of a neighbour list: plain pointers, copied by value into the kernel.
// A particle whose list overflowed its capacity is served by scanning the cells directly, so the
// result never depends on a capacity guess; the host grows the capacity for later builds.
#include "core/lanes.hpp"
#include "neighbour/cell_grid.hpp"
#include "neighbour/pair_filter.hpp"

namespace structmd {

template <class R>
struct NeighbourView {
    // Neighbour k of particle i at list[i * particleStride + k * entryStride]: by rows (a particle's
    // entries side by side, for several lanes per particle and for CPU caches) or by columns (entry k
    // of consecutive particles side by side, for one GPU thread per particle).
    int* list = nullptr;
    int* count = nullptr;
    int capacity = 0;
    int64_t particleStride = 0;
    int64_t entryStride = 0;

    SMD_HD SMD_INLINE int* entries_of(int64_t i) const { return list + i * particleStride; }
    int* cellCount = nullptr;
    int* cellParticles = nullptr;  // particle s of cell c at cellParticles[c * cellCapacity + s]
    Real4<R>* cellPositions = nullptr;  // its position when binned, in the same slot
    int cellCapacity = 0;
    int* overflow = nullptr;  // particles that did not fit in their cell
    int* overflowCount = nullptr;
    CellGrid<R> grid;
    Box<R> box;
    PairFilter filter;

    // Calls visit(j) for every candidate neighbour j != i that the filter accepts, in an order that
    // does not depend on thread timing; with several lanes, each lane visits its share. Candidates
    // may lie beyond the cutoff; the caller checks the distance.
    template <class Visit>
    SMD_HD SMD_INLINE void for_each_neighbour(int i, Vec3<R> ri, Visit&& visit, Lanes lanes = {}) const {
        const int n = count[i];
        if (n <= capacity) {
            const int* entries = entries_of(i);
            SMD_UNROLL4
            for (int k = lanes.lane; k < n; k += lanes.count) visit(entries[k * entryStride]);
            return;
        }
        int candidate = 0;
        scan_cells(i, ri, [&](int j) {
            if (candidate++ % lanes.count == lanes.lane) visit(j);
        });
    }

    // Candidates from the cells binned at the last build. A particle now at ri lies within
    // half a skin of where it was binned, so the adjacent cells of its current cell still hold
    // every particle within the list radius.
    template <class Visit>
    SMD_HD SMD_INLINE void scan_cells(int i, Vec3<R> ri, Visit&& visit) const {
        int cx, cy, cz;
        grid.coordinates(ri, box, cx, cy, cz);
        grid.for_each_adjacent(cx, cy, cz, [&](int c) {
            const int m = cellCount[c] < cellCapacity ? cellCount[c] : cellCapacity;
            const int* members = cellParticles + static_cast<int64_t>(c) * cellCapacity;
            for (int s = 0; s < m; ++s)
                if (members[s] != i && filter.accepts(i, members[s])) visit(members[s]);
        });
        const int extra = *overflowCount;
        for (int k = 0; k < extra; ++k)
            if (overflow[k] != i && filter.accepts(i, overflow[k])) visit(overflow[k]);
    }
};

}  // namespace structmd
