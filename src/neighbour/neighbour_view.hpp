#pragma once
// What a pair kernel sees of a neighbour list: plain pointers, copied by value into the kernel.
// A particle whose list overflowed its capacity is served by scanning the cells directly, so the
// result never depends on a capacity guess; the host grows the capacity for later builds.
#include "neighbour/cell_grid.hpp"
#include "neighbour/pair_filter.hpp"

namespace structmd {

template <class R>
struct NeighbourView {
    int* list = nullptr;  // neighbour k of particle i at list[k * stride + i]
    int* count = nullptr;
    int capacity = 0;
    int stride = 0;
    int* cellCount = nullptr;
    int* cellParticles = nullptr;  // particle s of cell c at cellParticles[c * cellCapacity + s]
    int cellCapacity = 0;
    int* overflow = nullptr;  // particles that did not fit in their cell
    int* overflowCount = nullptr;
    CellGrid<R> grid;
    Box<R> box;
    PairFilter filter;

    // Calls visit(j) for every candidate neighbour j != i that the filter accepts, in an order that
    // does not depend on thread timing. Candidates may lie beyond the cutoff; the caller checks the
    // distance.
    template <class Visit>
    SMD_HD SMD_INLINE void for_each_neighbour(int i, Vec3<R> ri, Visit&& visit) const {
        const int n = count[i];
        if (n <= capacity) {
            for (int k = 0; k < n; ++k) visit(list[k * stride + i]);
            return;
        }
        scan_cells(i, ri, visit);
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
