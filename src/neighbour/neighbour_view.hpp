#pragma once
// What a pair kernel sees of a neighbour list: plain pointers, copied by value into the kernel.
//
// The list works in its own order of the particles, by cell of the last build, so that particles
// close in space are close in memory: a warp's neighbours share cache lines, and a cell's members
// are one contiguous range. Slot k holds particle order[k]; the list keeps the positions of the
// current step in slot order (positions[k]), and its entries are slots.
//
// A particle whose list overflowed its capacity is served by scanning the cells directly, so the
// result never depends on a capacity guess; the host grows the capacity for later builds.
#include "core/lanes.hpp"
#include "neighbour/cell_grid.hpp"
#include "neighbour/pair_filter.hpp"
#include "state/cell_local_positions.hpp"

namespace structmd {

template <class R>
struct NeighbourView {
    const Real4<R>* positions = nullptr;  // this step's positions, by slot
    const Real4<R>* binned = nullptr;     // the positions of the last build, by slot
    const int* order = nullptr;           // the particle in each slot
    // Neighbour m of slot k at list[k * particleStride + m * entryStride]: by rows (a slot's entries
    // side by side, for several lanes per particle and for CPU caches) or by columns (entry m of
    // consecutive slots side by side, for one GPU thread per particle).
    int* list = nullptr;
    int* count = nullptr;
    int capacity = 0;
    int64_t particleStride = 0;
    int64_t entryStride = 0;
    const int* cellStart = nullptr;  // cell c holds slots cellStart[c] .. cellStart[c + 1] - 1
    CellGrid<R> grid;
    const int* batch = nullptr;  // batch by particle, numbered as the grid's batches; null: one batch
    Box<R> box;
    PairFilter filter;
    CellLocalPositions<R> cellLocal;  // this step's positions in float by slot, where the list keeps them

    SMD_HD SMD_INLINE int* entries_of(int64_t k) const { return list + k * particleStride; }
    SMD_HD SMD_INLINE int batch_of_slot(int64_t k) const { return batch ? batch[order[k]] : 0; }

    // Whether the pair of slots k and s may be listed (the filter judges particles, not slots).
    SMD_HD SMD_INLINE bool accepts(int k, int s) const {
        return s != k && (filter.trivial() || filter.accepts(order[k], order[s]));
    }

    // Calls visit(s) for every candidate neighbour slot s of slot k that the filter accepts, in an
    // order that does not depend on thread timing; with several lanes, each lane visits its share.
    // Candidates may lie beyond the cutoff; the caller checks the distance.
    template <class Visit>
    SMD_HD SMD_INLINE void for_each_neighbour(int k, Visit&& visit, Lanes lanes = {}) const {
        const int n = count[k];
        if (n <= capacity) {
            // The next entry is loaded before this one's visit, so that a neighbour's position is
            // one load away from its visit rather than two dependent loads. A pointer stepped along
            // the lane's entries, not the entry's index times the 64-bit stride each neighbour; its
            // last step, past the lane's last entry, is not read.
            int m = lanes.lane;
            const int64_t step = lanes.count * entryStride;
            const int* entry = entries_of(k) + m * entryStride;
            int s = m < n ? *entry : 0;
            SMD_UNROLL4
            for (; m < n; m += lanes.count) {
                entry += step;
                const int next = m + lanes.count < n ? *entry : 0;
                visit(s);
                s = next;
            }
            return;
        }
        int candidate = 0;
        scan_cells(k, [&](int s) {
            if (candidate++ % lanes.count == lanes.lane) visit(s);
        });
    }

    // Candidates from the cells of the last build, around the cell where slot k was binned: both
    // particles of a pair now within the list radius minus the skin were within the list radius
    // then, so in the same or adjacent cells.
    template <class Visit>
    SMD_HD SMD_INLINE void scan_cells(int k, Visit&& visit) const {
        int cx, cy, cz;
        grid.coordinates(xyz(binned[k]), box, cx, cy, cz);
        grid.for_each_adjacent(cx, cy, cz, batch_of_slot(k), [&](int c) {
            for (int s = cellStart[c]; s < cellStart[c + 1]; ++s)
                if (accepts(k, s)) visit(s);
        });
    }
};

}  // namespace structmd
