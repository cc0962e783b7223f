#pragma once
// Functors of the Verlet list build. Each runs on both backends; every one after the displacement
// check returns at once unless the device-side rebuild flag is set, so deciding whether to rebuild
// needs no trip to the host.
//
// A build is a counting sort of the particles by cell: count each cell's members (binning), turn
// the counts into each cell's first slot (a scan in chunks of cells), place every particle in its
// cell's range, sort each range by particle so the order does not depend on thread timing, and
// list each slot's neighbours from the ranges of the adjacent cells.
#include <cstdint>

#include "core/atomic.hpp"
#include "core/vec.hpp"
#include "neighbour/neighbour_view.hpp"
#include "state/slot_mirror.hpp"

#if SMD_HOST_CODE
#include "core/left_pack.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>
#endif

namespace structmd {

// Slots of the list's small control buffer.
enum ListControl : int {
    kRebuild = kListRebuildFlag,  // 1 from the step that needs a build until the build ends
    kBuilds = 1,         // number of builds since load
    kMaxNeighbours = 2,  // the longest list seen at a build
    kMaxPartnerClusters = 3,  // the longest cluster-pair list seen at a build (cluster_list_kernels.hpp)
    kControlSlots = 4
};

// Every step whose drift did not mirror the positions (state/drift_bookkeeping.hpp), and the first
// view() of a list whose mirror had left the slots' positions out: copies them into slot order with
// the displacement check (the drift's, for the same positions: it raises nothing new).
template <class R>
struct RefreshPositions {
    const Real4<R>* pos;
    const int* order;
    SlotMirror<R> mirror;
    SMD_HD void operator()(int64_t k) const { mirror.record(k, pos[order[k]]); }
};

template <class R>
struct BinParticles {
    const Real4<R>* pos;
    CellGrid<R> grid;
    const int* batch;  // null: one batch
    Box<R> box;
    int* control;
    int* cellCount;
    int* cellOf;
    int* rankInCell;
    SMD_HD void operator()(int64_t i) const {
        if (!control[kRebuild]) return;
        int cx, cy, cz;
        grid.coordinates(xyz(pos[i]), box, cx, cy, cz);
        const int c = grid.index(cx, cy, cz, batch ? batch[i] : 0);
        cellOf[i] = c;
        rankInCell[i] = atomic_add(cellCount + c, 1);
    }
};

// The members of each chunk of cells, summed by the chunk's lanes.
struct SumCellChunks {
    const int* control;
    const int* cellCount;
    int* chunkTotal;
    int chunkCells;
    int cells;
    SMD_HD void operator()(int64_t chunk, Lanes lanes) const {
        if (!control[kRebuild]) return;
        const int first = static_cast<int>(chunk) * chunkCells;
        const int last = first + chunkCells < cells ? first + chunkCells : cells;
        int total = 0;
        for (int c = first + lanes.lane; c < last; c += lanes.count) total += cellCount[c];
        total = lanes.sum(total);
        if (lanes.leader()) chunkTotal[chunk] = total;
    }
};

// The first slot of every cell of a chunk: the members of the chunks before it and of the cells
// before it in the chunk, the lanes taking the chunk's cells in rounds. Each memory access of the
// lanes is independent of the others, so neither pass waits on one load after another. The
// counts are cleared for the next build on the way.
struct StartCells {
    int* control;
    int* cellCount;
    const int* chunkTotal;
    int* cellStart;
    int chunkCells;
    int cells;
    SMD_HD void operator()(int64_t chunk, Lanes lanes) const {
        if (!control[kRebuild]) return;
        int start = 0;
        for (int64_t before = lanes.lane; before < chunk; before += lanes.count) start += chunkTotal[before];
        start = lanes.sum(start);
        const int first = static_cast<int>(chunk) * chunkCells;
        const int last = first + chunkCells < cells ? first + chunkCells : cells;
        for (int base = first; base < last; base += lanes.count) {
            const int c = base + lanes.lane;
            const int members = c < last ? cellCount[c] : 0;
            int round = 0;
            const int below = lanes.exclusive_sum(members, round);
            if (c < last) {
                cellStart[c] = start + below;
                cellCount[c] = 0;
            }
            start += round;
        }
        if (last == cells && lanes.leader()) {
            cellStart[cells] = start;
            control[kBuilds] += 1;
        }
    }
};

struct PlaceParticles {
    const int* control;
    const int* cellOf;
    const int* rankInCell;
    const int* cellStart;
    int* order;
    SMD_HD void operator()(int64_t i) const {
        if (!control[kRebuild]) return;
        order[cellStart[cellOf[i]] + rankInCell[i]] = static_cast<int>(i);
    }
};

SMD_HD SMD_INLINE void insertion_sort(int* a, int n) {
    for (int k = 1; k < n; ++k) {
        const int v = a[k];
        int m = k - 1;
        while (m >= 0 && a[m] > v) {
            a[m + 1] = a[m];
            --m;
        }
        a[m + 1] = v;
    }
}

// In place and in n log n, for the rare crowded cell (a collapsed or badly started system) where
// insertion sort's n^2 would stall the build.
SMD_HD SMD_INLINE void heap_sort(int* a, int n) {
    const auto sift_down = [a](int root, int end) {
        while (2 * root + 1 < end) {
            int child = 2 * root + 1;
            if (child + 1 < end && a[child] < a[child + 1]) ++child;
            if (!(a[root] < a[child])) return;
            const int t = a[root];
            a[root] = a[child];
            a[child] = t;
            root = child;
        }
    };
    for (int root = n / 2 - 1; root >= 0; --root) sift_down(root, n);
    for (int end = n - 1; end > 0; --end) {
        const int t = a[0];
        a[0] = a[end];
        a[end] = t;
        sift_down(0, end);
    }
}

// Each cell's range sorted by particle, so the slots, the lists and the order of force sums are
// the same on every run and every thread count; then the positions copied into slot order, as
// this step's and as the reference for the displacement check, and each particle's slot noted.
// Where the list keeps cell-local positions, the reference's w takes the cell's packed coordinates.
template <class R>
struct SortCells {
    const Real4<R>* pos;
    const int* control;
    const int* cellStart;
    int* order;
    int* slotOf;
    Real4<R>* positions;
    Real4<R>* binned;
    CellGrid<R> grid;
    CellLocalPositions<R> cellLocal;
    Box<R> box;
    SMD_HD void operator()(int64_t c) const {
        if (!control[kRebuild]) return;
        const int first = cellStart[c], members = cellStart[c + 1] - first;
        if (members <= 32)
            insertion_sort(order + first, members);
        else
            heap_sort(order + first, members);
        float packed = 0;
        if (cellLocal.local) {
            int cx, cy, cz;
            grid.coordinates_of(static_cast<int>(c), cx, cy, cz);
            packed = cellLocal.pack(cx, cy, cz);
        }
        for (int s = first; s < first + members; ++s) {
            const Real4<R> p = pos[order[s]];
            positions[s] = p;
            binned[s] = p;
            slotOf[order[s]] = s;
            if (cellLocal.local) {
                binned[s].w = R(packed);
                cellLocal.local[s] = cellLocal.of(xyz(p), packed, box);
            }
        }
    }
};

// Each slot's lanes take the candidates of a cell in rounds, one candidate per lane, and append
// those within the list radius in lane order: the list comes out in cell order, independent of
// thread timing. Where the list keeps cell-local positions (mixed precision), the candidates'
// distances are taken from those, half the bytes of the double positions.
template <class R>
struct BuildLists {
    NeighbourView<R> view;
    R listRadius2;
    int* control;
    bool byParticle;  // sort each list by particle (see below)

    // How a candidate's separation is taken: the minimum image of the positions (any grid), the
    // positions plus the image shift of the candidate's cell (a grid where images_by_offset()), or
    // the list's cell-local positions plus the cells' distance.
    enum Separations { kMinimumImage, kCellImage, kCellLocal };

    // Lists slot k's candidates within the list radius, returns how many, from the cells that
    // come within the list radius of the slot's position, a row's run of them at a time. The image
    // of a run's cells is the same for all their members, so it is taken once a run, and a
    // candidate costs a load, a difference and a distance. With cell-local positions the cells'
    // distance along x differs from cell to cell of a run, and each candidate takes it from its own
    // cell's code (CellLocalPositions::RowShift): one addition more a candidate, where taking the
    // cells one by one cost the mixed-precision build half as many instructions again as single's
    // (ncu, 1M, H200).
    template <Separations kHow, bool kAnyPair>
    SMD_HD SMD_INLINE int collect(int64_t k, Lanes lanes) const {
        const NeighbourView<R>& v = view;
        const int self = static_cast<int>(k);
        const int particle = kAnyPair ? 0 : v.order[k];  // for the filter
        const PairFilter::FewExclusions exclusions = kAnyPair ? PairFilter::FewExclusions{} : v.filter.few_exclusions_of(particle);
        const Vec3<R> rk = xyz(v.positions[k]);
        const Real4<float> localK = kHow == kCellLocal ? v.cellLocal.local[k] : Real4<float>{0.0f, 0.0f, 0.0f, 0.0f};
        const float localRadius2 = static_cast<float>(listRadius2);
        int* const entries = v.entries_of(k);
        int n = 0;
        // One lane stages its entries and writes each four as one chunk at `chunk`: staged in
        // shared memory on the GPU, where four more registers made the lone-lane kernels spill
        // 3-4 times the bytes (sm_90), in a local array on the host.
        constexpr int kChunk = NeighbourView<R>::kChunk;
        static_assert((kChunk & (kChunk - 1)) == 0, "a chunk's place is taken by a mask");
        int* chunk = entries;
#if defined(__CUDA_ARCH__)
        __shared__ int staged[kChunk * kBlockThreads];
        int* const stage = staged + threadIdx.x;
        constexpr int kStageStride = kBlockThreads;
#else
        int staged[kChunk] = {};
        int* const stage = staged;
        constexpr int kStageStride = 1;
#endif
        const auto staged_chunk = [&] {
            return EntryChunk{{stage[0], stage[kStageStride], stage[2 * kStageStride], stage[3 * kStageStride]}};
        };
        int cx, cy, cz;
        v.grid.coordinates(rk, v.box, cx, cy, cz);
        const Vec3<R> u = v.grid.scaled(rk, v.box);
        const R prune2 = v.grid.pruning_radius2(listRadius2);
        // Candidates begin .. end - 1, each lane taking one a round; cells: their cells' distance
        // from slot k's (cell-local positions), image: their image shift (kCellImage), rowOffset:
        // the cells' offset along y and z as entry bits (lists whose entries carry it).
        const bool offsetEntries = kHow == kCellLocal && v.entryShift != 0;
        const auto scan = [&](int begin, int end, const typename CellLocalPositions<R>::RowShift& cells,
                              const Vec3<R>& image, int rowOffset) {
            for (int base = begin; base < end; base += lanes.count) {
                const int s = base + lanes.lane;
                // The slot itself (one candidate of some two hundred) is dropped after the distance,
                // which it passes, so the others take no branch for it.
                bool accepted = s < end;
                float cellsAlongX = 0.0f;  // the candidate's cells from the slot's along x (cell-local)
                if (accepted && kHow == kCellLocal) {
                    const Real4<float> candidate = v.cellLocal.local[s];
                    cellsAlongX = cells.along_x(candidate);
                    const Vec3<float> d = v.cellLocal.separation(localK, candidate, cells, cellsAlongX);
                    accepted = dot(d, d) < localRadius2;
                } else if (accepted) {
                    // (x_s - x_k) + shift rounds as the minimum image's (x_s - x_k) -+ L does.
                    const Vec3<R> d = kHow == kCellImage ? (xyz(v.positions[s]) - rk) + image
                                                         : v.box.minimum_image(xyz(v.positions[s]) - rk);
                    accepted = dot(d, d) < listRadius2;
                }
                accepted = accepted && s != self;
                // The filter after the distance: it looks the partner up (its particle, compared
                // with the slot's few exclusions or a search of many), and about one candidate in six
                // is within the list radius.
                if (!kAnyPair && accepted) accepted = v.filter.accepts(particle, v.order[s], exclusions);
                // The entry: the slot, or with its cells' offset (along x an exact small integer in
                // float, kept from the distance: loading the candidate again cost the mixed build
                // spills under its register cap).
                const int entry = !offsetEntries || !accepted
                                      ? s
                                      : CellLocalPositions<R>::entry(s, rowOffset | (static_cast<int>(cellsAlongX) + 2));
                if (lanes.count == 1) {
                    if (!accepted) continue;
                    stage[(n & (kChunk - 1)) * kStageStride] = entry;  // n % kChunk, n not negative
                    if ((++n & (kChunk - 1)) == 0) {
                        if (n <= v.capacity) NeighbourView<R>::store_chunk(chunk, staged_chunk());
                        chunk += v.chunkStride;
                    }
                    continue;
                }
                int found = 0;
                const int rank = lanes.rank_among(accepted, found);
                if (accepted && n + rank < v.capacity) entries[v.offset_of(n + rank)] = entry;
                n += found;
            }
        };
        v.grid.template for_each_run_near<true>(u, cx, cy, cz, v.batch_of_slot(k), prune2, [&](int first, int last, int dx, int dy, int dz) {
            const CellGrid<R>& g = v.grid;
            Vec3<R> image{R(0), R(0), R(0)};
            typename CellLocalPositions<R>::RowShift cells{};
            const int rowOffset = offsetEntries ? CellLocalPositions<R>::offset_bits(-2, dy, dz) : 0;
            if (kHow == kCellLocal) {
                cells = v.cellLocal.row_shift(CellGrid<R>::periodic(cx + dx, g.nx), CellGrid<R>::periodic(cy + dy, g.ny),
                                              CellGrid<R>::periodic(cz + dz, g.nz), dx, dy, dz);
            } else if (kHow == kCellImage) {
                image = {CellGrid<R>::image_shift(cx, dx, g.nx, v.box.length.x, g.openX),
                         CellGrid<R>::image_shift(cy, dy, g.ny, v.box.length.y, g.openY),
                         CellGrid<R>::image_shift(cz, dz, g.nz, v.box.length.z, g.openZ)};
            }
            scan(v.cellStart[first], v.cellStart[last + 1], cells, image, rowOffset);
        });
        // One lane's last, partial chunk (its other places hold what no reader visits).
        if (lanes.count == 1 && n % kChunk != 0 && n <= v.capacity) NeighbourView<R>::store_chunk(chunk, staged_chunk());
        return n;
    }

#if SMD_HOST_CODE
    // How this view's separations are taken, chosen on the host for a whole build (BuildListsAlong).
    Separations separations() const {
        return view.cellLocal.local ? kCellLocal : view.grid.images_by_offset() ? kCellImage : kMinimumImage;
    }
#endif

    // Slot k's list, its separations taken as kHow says; kAnyPair where the filter is trivial().
    template <Separations kHow, bool kAnyPair>
    SMD_HD SMD_INLINE void build(int64_t k, Lanes lanes) const {
        if (!control[kRebuild]) return;
        const int n = collect<kHow, kAnyPair>(k, lanes);
        if (!lanes.leader()) return;
        const NeighbourView<R>& v = view;
        int* entries = v.entries_of(k);
        // In particle order, so a particle's force sum does not depend on where the particles
        // happened to be at this build: a restarted run repeats the same sums bit for bit.
        const int stored = !byParticle ? 0 : (n < v.capacity ? n : v.capacity);
        for (int m = 1; m < stored; ++m) {
            const int value = entries[v.offset_of(m)];
            int before = m - 1;
            while (before >= 0 && v.order[v.slot_of_entry(entries[v.offset_of(before)])] > v.order[v.slot_of_entry(value)]) {
                entries[v.offset_of(before + 1)] = entries[v.offset_of(before)];
                --before;
            }
            entries[v.offset_of(before + 1)] = value;
        }
        v.count[k] = n;
        atomic_max(control + kMaxNeighbours, n);
    }

#if SMD_HOST_CODE
    // Rows are skipped for reaches up to this (the CPU's lists use 2); a wider one scans every cell.
    static constexpr int kMaxRowReach = 4;

    // A list of up to this many entries is put in particle order by ranking (below); a longer one,
    // in a crowded or collapsed system, by a sort in n log n.
    static constexpr int kRankedListLimit = 256;

    // The CPU backend's loop (backends/cpu/cpu_backend.hpp, for_each_lanes): slots begin .. end - 1 on
    // one thread, the same lists as build() with one lane. Each accepted candidate's slot is kept,
    // then its particle looked up, and each goes to its place in particle order: the number
    // of smaller particles in the list (particles in a list are distinct). That count is a loop of
    // independent compares the compiler vectorises, where a comparison sort's branches, mispredicted
    // about half the time, took a third of the build. flatten: the minimum image and the cell
    // arithmetic inlined into the candidate loop.
    SMD_HOST_LOOP void host_rows(int64_t begin, int64_t end) const {
        if (!control[kRebuild]) return;
        const NeighbourView<R>& v = view;
        const int capacity = v.capacity > 0 ? v.capacity : 0;
        // Eight spare places past the capacity: a block of candidates beyond it is written there and
        // dropped.
        thread_local std::vector<int> particles, slots;
        thread_local std::vector<uint64_t> keys;
        thread_local std::vector<int16_t> keys16;
        thread_local std::vector<R> distance2;
        if (slots.size() < static_cast<size_t>(capacity) + 8) {
            particles.resize(static_cast<size_t>(capacity) + 8);
            keys16.resize(static_cast<size_t>(capacity) + 8);
            slots.resize(static_cast<size_t>(capacity) + 8);
        }
        int* const particle = particles.data();
        int* const slot = slots.data();
        const Real4<R>* const positions = v.positions;
        const int* const order = v.order;
        const Box<R> box = v.box;
        const R radius2 = listRadius2;
        const R prune2 = v.grid.pruning_radius2(listRadius2);
        const Vec3<R> width{R(1) / v.grid.cellsPerLength.x, R(1) / v.grid.cellsPerLength.y,
                            R(1) / v.grid.cellsPerLength.z};
        const bool trivial = v.filter.trivial();
        const int slotCount =
            v.cellStart[static_cast<int64_t>(v.grid.nx) * v.grid.ny * v.grid.nz * v.grid.batches];
        int longest = 0;
        for (int64_t k = begin; k < end; ++k) {
            const Vec3<R> rk = xyz(positions[k]);
            int n = 0;
            // Candidates s in first .. last - 1.
            const auto scan = [&](int first, int last) {
                const Real4<R>* const candidate = positions + first;
                const int candidates = last - first;
                const Box<R> cellBox = box;
                const R x = rk.x, y = rk.y, z = rk.z;
                const auto distance2_of = [&](int m) {
                    const Vec3<R> d = cellBox.minimum_image(
                        Vec3<R>{candidate[m].x - x, candidate[m].y - y, candidate[m].z - z});
                    return dot(d, d);
                };
                if (trivial && last + 7 <= slotCount) {
                    // Eight candidates at a time, reading up to seven slots past the last (a row
                    // holds about ten: a vectorised loop's set-up and scalar tail would cost more
                    // than the loop), the accepted ones appended without a branch (a branch on the
                    // distance is mispredicted about half the time).
                    for (int m = 0; m < candidates; m += 8) {
                        unsigned accepted = 0;
                        for (int e = 0; e < 8; ++e)
                            accepted |= static_cast<unsigned>((distance2_of(m + e) < radius2) & (first + m + e != k) &
                                                              (e < candidates - m))
                                        << e;
                        n += LeftPack<int32_t>::append_indices(slot + (n < capacity ? n : capacity), first + m, accepted);
                    }
                    return;
                }
                // The squared distances first, in a loop of their own that the compiler
                // vectorises (no `omp simd`: g++ 12 then declines it, "no vectype"), then the
                // accepted ones appended.
                if (distance2.size() < static_cast<size_t>(candidates)) distance2.resize(static_cast<size_t>(candidates) * 2);
                R* const d2 = distance2.data();
                for (int m = 0; m < candidates; ++m) d2[m] = distance2_of(m);
                for (int s = first; s < last; ++s) {
                    const bool accepted = d2[s - first] < radius2 && s != k && (trivial || v.accepts(static_cast<int>(k), s));
                    slot[n < capacity ? n : capacity] = s;
                    n += accepted;
                }
            };
            int cx, cy, cz;
            v.grid.coordinates(rk, box, cx, cy, cz);
            const CellGrid<R>& grid = v.grid;
            const int reach = grid.reach;
            const Vec3<R> u = grid.scaled(rk, box);
            if (byParticle && reach <= kMaxRowReach && grid.prunable_at(u)) {
                // The cells of a row along x are consecutive slots, scanned as one range (the list
                // is sorted by particle below, so the order of discovery does not matter). A row
                // whose cells all lie beyond the list radius in y and z is skipped, and a row is
                // scanned only over the cells the radius reaches along x from this particle. These
                // are CellGrid::for_each_run_near's runs, which the GPU's build takes; computed here
                // from gaps tabled once an axis and a square root for the row's extent, where that
                // function's gap per cell cost this loop 8.8% more instructions (32,000 particles,
                // callgrind). One form for both waits on a GPU measurement of this one.
                R gapY2[2 * kMaxRowReach + 1], gapZ2[2 * kMaxRowReach + 1];
                for (int d = -reach; d <= reach; ++d) {
                    const R gy = CellGrid<R>::gap(u.y, cy, d) * width.y, gz = CellGrid<R>::gap(u.z, cz, d) * width.z;
                    gapY2[d + reach] = gy * gy;
                    gapZ2[d + reach] = gz * gz;
                }
                // Offsets that keep u.x -/+ the reach along x positive, where truncation is floor.
                const int shift = reach + 2;
                const int batch = v.batch_of_slot(k);
                for (int dz = -reach; dz <= reach; ++dz) {
                    if (gapZ2[dz + reach] >= prune2) continue;
                    const int pz = CellGrid<R>::periodic(cz + dz, grid.nz);
                    for (int dy = -reach; dy <= reach; ++dy) {
                        const R left2 = prune2 - gapY2[dy + reach] - gapZ2[dz + reach];
                        if (left2 <= R(0)) continue;
                        const R along = std::sqrt(left2) * grid.cellsPerLength.x;
                        const int low = static_cast<int>(u.x - along + R(shift)) - shift;
                        const int high = static_cast<int>(u.x + along + R(shift)) - shift;
                        int first = low > cx - reach ? low : cx - reach;
                        int last = high < cx + reach ? high : cx + reach;
                        const int row = grid.index(0, CellGrid<R>::periodic(cy + dy, grid.ny), pz, batch);
                        if (first < 0) {
                            scan(v.cellStart[row + first + grid.nx], v.cellStart[row + grid.nx]);
                            first = 0;
                        }
                        if (last >= grid.nx) {
                            scan(v.cellStart[row], v.cellStart[row + last - grid.nx + 1]);
                            last = grid.nx - 1;
                        }
                        if (first <= last) scan(v.cellStart[row + first], v.cellStart[row + last + 1]);
                    }
                }
            } else {
                grid.for_each_adjacent(cx, cy, cz, v.batch_of_slot(k),
                                       [&](int c) { scan(v.cellStart[c], v.cellStart[c + 1]); });
            }
            const int stored = n < capacity ? n : capacity;
            // In particle order, as build() leaves it (a list in cell order needs no sort).
            int* entries = v.entries_of(k);
            if (!byParticle) {
                for (int m = 0; m < stored; ++m) entries[v.offset_of(m)] = slot[m];
            } else if (stored <= kRankedListLimit) {
                int low = std::numeric_limits<int>::max(), high = std::numeric_limits<int>::min();
                for (int m = 0; m < stored; ++m) {
                    particle[m] = order[slot[m]];
                    low = particle[m] < low ? particle[m] : low;
                    high = particle[m] > high ? particle[m] : high;
                }
                // Each entry to its place: the count of smaller keys, with a key's own type as
                // the counter (a list never holds more than kRankedListLimit).
                const auto rank_by = [&](const auto* key) {
                    using Key = std::remove_cv_t<std::remove_pointer_t<decltype(key)>>;
                    for (int m = 0; m < stored; ++m) {
                        const Key id = key[m];
                        Key rank = 0;
                        for (int other = 0; other < stored; ++other) rank += key[other] < id;
                        entries[v.offset_of(rank)] = slot[m];
                    }
                };
                if (stored > 0 && high - low <= std::numeric_limits<int16_t>::max()) {
                    // Particles within 32,768 of each other (every list of a system that small):
                    // compared in 16-bit lanes, twice as many a vector.
                    int16_t* const key = keys16.data();
                    for (int m = 0; m < stored; ++m) key[m] = static_cast<int16_t>(particle[m] - low);
                    rank_by(key);
                } else {
                    rank_by(particle);
                }
            } else {
                if (keys.size() < static_cast<size_t>(stored)) keys.resize(static_cast<size_t>(stored));
                for (int m = 0; m < stored; ++m)
                    keys[m] = static_cast<uint64_t>(static_cast<uint32_t>(order[slot[m]])) << 32 | static_cast<uint32_t>(slot[m]);
                std::sort(keys.begin(), keys.begin() + stored);
                for (int m = 0; m < stored; ++m) entries[v.offset_of(m)] = static_cast<int>(static_cast<uint32_t>(keys[m]));
            }
            v.count[k] = n;
            longest = n > longest ? n : longest;
        }
        atomic_max(control + kMaxNeighbours, longest);
    }
#endif
};

// BuildLists with its separations and its filter fixed at launch (with_build_path): the path's own
// GPU kernel, which holds no other path's registers. The six in one kernel, chosen per slot, spilled
// 1,012/1,196 bytes a thread (stores/loads, double, the lone-lane kernel's register cap, sm_90); the
// cell-local path for any pair alone 104/100. The CPU backend runs the inherited host_rows whatever
// the path.
template <class R, typename BuildLists<R>::Separations kHow, bool kAnyPair>
struct BuildListsAlong : BuildLists<R> {
    SMD_HD void operator()(int64_t k, Lanes lanes) const { this->template build<kHow, kAnyPair>(k, lanes); }
};

#if SMD_HOST_CODE
// launch(along): `lists` as the BuildListsAlong of the path its view calls for.
template <class R, class Launch>
void with_build_path(const BuildLists<R>& lists, Launch&& launch) {
    using L = BuildLists<R>;
    const auto filtered = [&](auto how) {
        constexpr typename L::Separations kHow = decltype(how)::value;
        if (lists.view.filter.trivial())
            launch(BuildListsAlong<R, kHow, true>{lists});
        else
            launch(BuildListsAlong<R, kHow, false>{lists});
    };
    switch (lists.separations()) {
        case L::kCellLocal: return filtered(std::integral_constant<typename L::Separations, L::kCellLocal>{});
        case L::kCellImage: return filtered(std::integral_constant<typename L::Separations, L::kCellImage>{});
        case L::kMinimumImage: return filtered(std::integral_constant<typename L::Separations, L::kMinimumImage>{});
    }
}
#endif

}  // namespace structmd
