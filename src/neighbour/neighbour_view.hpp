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

// Four list entries, which one GPU thread reads or writes with one 16-byte access.
struct alignas(16) EntryChunk {
    int entry[4];
};

template <class R>
struct NeighbourView {
    static constexpr int kChunk = 4;  // entries a chunk
    const Real4<R>* positions = nullptr;  // this step's positions, by slot
    const Real4<R>* binned = nullptr;     // the positions of the last build, by slot
    const int* order = nullptr;           // the particle in each slot
    // Neighbour m of slot k at list[k * particleStride + (m / 4) * chunkStride + m % 4], the capacity
    // a multiple of 4: by rows (particleStride the capacity, chunkStride 4: a slot's entries side by
    // side, for several lanes per particle, which the GPU's readers take where it lays the list out so,
    // and for CPU caches) or by columns of chunks (particleStride 4, chunkStride 4 x the slots: a
    // slot's entries four at a time, the fours of consecutive slots side by side, for one GPU thread
    // per particle: a warp's threads read their next four in 512 contiguous bytes, and the list
    // build writes four at once, where writing its entries one by one sent the L2 cache a sector
    // for each four bytes, 69% of the L2's throughput in a build at 1M, H200).
    int* list = nullptr;
    int* count = nullptr;
    int capacity = 0;
    int64_t particleStride = 0;
    int64_t chunkStride = 0;
    // 0: an entry is a slot. CellLocalPositions::kOffsetBits: an entry is a slot and its pair's
    // cells' offset (CellLocalPositions::entry), the GPU's lists (by rows or columns) with
    // cell-local positions, whose pair kernels take the offset from it.
    int entryShift = 0;
    const int* cellStart = nullptr;  // cell c holds slots cellStart[c] .. cellStart[c + 1] - 1
    CellGrid<R> grid;
    const int* batch = nullptr;  // batch by particle, numbered as the grid's batches; null: one batch
    Box<R> box;
    PairFilter filter;
    CellLocalPositions<R> cellLocal;  // this step's positions in float by slot, where the list keeps them

    SMD_HD SMD_INLINE int* entries_of(int64_t k) const { return list + k * particleStride; }
    // Where entry m lies from entries_of(k).
    SMD_HD SMD_INLINE int64_t offset_of(int m) const { return (m / kChunk) * chunkStride + m % kChunk; }
    SMD_HD SMD_INLINE bool by_rows() const { return chunkStride == kChunk; }
    SMD_HD SMD_INLINE int batch_of_slot(int64_t k) const { return batch ? batch[order[k]] : 0; }

    // Whether the pair of slots k and s may be listed (the filter judges particles, not slots).
    SMD_HD SMD_INLINE bool accepts(int k, int s) const {
        return s != k && (filter.trivial() || filter.accepts(order[k], order[s]));
    }

    SMD_HD SMD_INLINE int slot_of_entry(int entry) const { return static_cast<int>(static_cast<unsigned>(entry) >> entryShift); }

    // Calls visit(s) for every candidate neighbour slot s of slot k that the filter accepts, in an
    // order that does not depend on thread timing; with several lanes, each lane visits its share.
    // Candidates may lie beyond the cutoff; the caller checks the distance. Several lanes read a list
    // by rows (the GPU lays a list out by rows where its readers take several lanes a particle).
    template <class Visit>
    SMD_HD SMD_INLINE void for_each_neighbour(int k, Visit&& visit, Lanes lanes = {}) const {
        for_each_entry(k, [&](int entry) { visit(slot_of_entry(entry)); }, visit, lanes);
    }

    // for_each_neighbour's traversal with the list's entries as they are: listed(entry) for each
    // entry of the list, scanned(s) for each slot of a list that overflowed (its cells scanned).
    template <class Listed, class Scanned>
    SMD_HD SMD_INLINE void for_each_entry(int k, Listed&& listed, Scanned&& scanned, Lanes lanes = {}) const {
        const int n = count[k];
        if (n <= capacity && lanes.count == 1) {
            // A chunk at a time, the next loaded before this one's visits, so that a neighbour's
            // position is one load away from its visit rather than two dependent loads. The last
            // step of the pointer, past the slot's last chunk, is not read.
            const int* chunk = entries_of(k);
            EntryChunk four = n > 0 ? load_chunk(chunk) : EntryChunk{};
            for (int m = 0; m < n; m += kChunk) {
                chunk += chunkStride;
                const EntryChunk next = m + kChunk < n ? load_chunk(chunk) : EntryChunk{};
                SMD_UNROLL
                for (int e = 0; e < kChunk; ++e)
                    if (m + e < n) listed(four.entry[e]);
                four = next;
            }
            return;
        }
        if (n <= capacity) {
            // By rows: as above, an entry at a time, the lane's entries lanes.count apart.
            int m = lanes.lane;
            const int* entry = entries_of(k) + m;
            int s = m < n ? *entry : 0;
            SMD_UNROLL4
            for (; m < n; m += lanes.count) {
                entry += lanes.count;
                const int next = m + lanes.count < n ? *entry : 0;
                listed(s);
                s = next;
            }
            return;
        }
        int candidate = 0;
        scan_cells(k, [&](int s) {
            if (candidate++ % lanes.count == lanes.lane) scanned(s);
        });
    }

    // The four entries at `at` (16-byte aligned): one load on the GPU.
    static SMD_HD SMD_INLINE EntryChunk load_chunk(const int* at) {
#if defined(__CUDA_ARCH__)
        return *reinterpret_cast<const EntryChunk*>(at);
#else
        return EntryChunk{{at[0], at[1], at[2], at[3]}};
#endif
    }
    static SMD_HD SMD_INLINE void store_chunk(int* at, const EntryChunk& four) {
#if defined(__CUDA_ARCH__)
        *reinterpret_cast<EntryChunk*>(at) = four;
#else
        for (int e = 0; e < kChunk; ++e) at[e] = four.entry[e];
#endif
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
