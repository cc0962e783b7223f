// The Verlet list against an all-pairs search: every pair within the cutoff must be visited, after
// builds, after moves that stay under the rebuild threshold, when the list overflows its capacity
// or a cell is crowded, in boxes with fewer than three cells per side, and with the CPU's cells half
// the list radius wide. The particles' order by
// cell must be a permutation that keeps each cell contiguous and does not depend on thread timing.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "backends/cpu/cpu_backend.hpp"
#include "forcefield/lennard_jones.hpp"
#include "forcefield/pair_kernel.hpp"
#include "neighbour/verlet_list.hpp"
#include "neighbour/verlet_list_kernels.hpp"
#include "random_particles.hpp"

namespace structmd {
namespace {

using List = VerletList<CpuBackend, double>;

struct System : RandomParticles {
    using RandomParticles::RandomParticles;

    // Pairs of particles, as the list offers them through its slots.
    std::set<std::pair<int, int>> visited(List& list) {
        list.update(pos, n, box, ++version);
        const NeighbourView<double> view = list.view();
        std::set<std::pair<int, int>> seen;
        for (int k = 0; k < n; ++k) {
            const int i = view.order[k];
            EXPECT_EQ(xyz(view.positions[k]).x, xyz(pos.data()[i]).x) << "slot " << k << " holds a stale position";
            view.for_each_neighbour(k, [&](int s) {
                const int j = view.order[s];
                EXPECT_NE(i, j) << "a particle was offered as its own neighbour";
                EXPECT_TRUE(seen.insert({i, j}).second) << "pair (" << i << ", " << j << ") visited twice";
            });
        }
        return seen;
    }

    // The particle in each slot, and each slot's list as particles in list order.
    std::pair<std::vector<int>, std::vector<std::vector<int>>> slots_and_lists(List& list) {
        list.update(pos, n, box, ++version);
        const NeighbourView<double> view = list.view();
        std::vector<int> order(view.order, view.order + n);
        std::vector<std::vector<int>> lists(n);
        for (int k = 0; k < n; ++k) view.for_each_neighbour(k, [&](int s) { lists[k].push_back(view.order[s]); });
        return {order, lists};
    }
};

// Every pair within the cutoff is among the visited candidates.
void expect_complete(const std::set<std::pair<int, int>>& wanted, const std::set<std::pair<int, int>>& seen) {
    int missing = 0;
    for (const auto& p : wanted)
        if (!seen.count(p)) ++missing;
    EXPECT_EQ(missing, 0) << "of " << wanted.size() << " pairs within the cutoff";
}

TEST(VerletList, FindsEveryPairAfterABuild) {
    System s(800, 12.0, 13.0, 14.0, 1);
    List list(s.backend, 2.5, 1.12, PairCondition::all, {}, nullptr, 1, nullptr);
    expect_complete(s.pairs_within(2.5), s.visited(list));
    list.adapt();
    EXPECT_EQ(list.builds(), 1);
}

// Several lanes share out a slot's entries as a GPU warp's do: lane l visits entries l, l + count,
// ... of the one-lane order, each once, also where a slot has fewer entries than lanes.
TEST(VerletList, LanesShareOutASlotsEntriesInTheOneLaneOrder) {
    System s(800, 12.0, 13.0, 14.0, 1);
    List list(s.backend, 2.5, 1.12, PairCondition::all, {}, nullptr, 1, nullptr);
    const auto [order, lists] = s.slots_and_lists(list);
    const NeighbourView<double> view = list.view();
    int fewerThanLanes = 0;
    for (int count : {2, 4, 8, 32})
        for (int k = 0; k < s.n; ++k) {
            const std::vector<int>& all = lists[k];
            if (int(all.size()) < count) ++fewerThanLanes;
            for (int lane = 0; lane < count; ++lane) {
                std::vector<int> wanted, seen;
                for (size_t m = lane; m < all.size(); m += count) wanted.push_back(all[m]);
                view.for_each_neighbour(k, [&](int t) { seen.push_back(view.order[t]); }, Lanes{lane, count});
                EXPECT_EQ(seen, wanted) << "slot " << k << ", lane " << lane << " of " << count;
            }
        }
    EXPECT_GT(fewerThanLanes, 0) << "no slot had fewer entries than lanes";
}

TEST(VerletList, StillCompleteAfterMovesBelowHalfTheSkin) {
    System s(800, 12.0, 12.0, 12.0, 2);
    List list(s.backend, 2.5, 1.12, PairCondition::all, {}, nullptr, 1, nullptr);  // skin 0.3
    s.visited(list);
    for (int k = 0; k < 5; ++k) {
        s.jiggle(0.029, 10 + k);  // five moves of 0.029: at most 0.145 < 0.15, no rebuild
        expect_complete(s.pairs_within(2.5), s.visited(list));
    }
    list.adapt();
    EXPECT_EQ(list.builds(), 1) << "moves under half the skin must not trigger a rebuild";
}

TEST(VerletList, RebuildsOnceAParticleMovesPastHalfTheSkin) {
    System s(500, 12.0, 12.0, 12.0, 3);
    List list(s.backend, 2.5, 1.12, PairCondition::all, {}, nullptr, 1, nullptr);
    s.visited(list);
    s.jiggle(0.16, 7);
    expect_complete(s.pairs_within(2.5), s.visited(list));
    list.adapt();
    EXPECT_EQ(list.builds(), 2);
}

TEST(VerletList, ForcedRebuildAfterInvalidate) {
    System s(300, 10.0, 10.0, 10.0, 4);
    List list(s.backend, 2.0, 1.2, PairCondition::all, {}, nullptr, 1, nullptr);
    s.visited(list);
    list.invalidate();
    s.visited(list);
    list.adapt();
    EXPECT_EQ(list.builds(), 2);
}

TEST(VerletList, CompleteWhenEveryParticleSitsInOneCell) {
    // All particles within a small blob: one crowded cell (sorted by the heap sort) and lists that
    // overflow their first capacity guess, so the cell-scan fallback must still find every pair;
    // the next build fits in the enlarged capacity.
    System s(400, 20.0, 20.0, 20.0, 5);
    for (int64_t i = 0; i < s.n; ++i) {
        Real4<double>& p = s.pos.data()[i];
        p = {0.05 * p.x, 0.05 * p.y, 0.05 * p.z, 0.0};
    }
    List list(s.backend, 2.5, 1.1, PairCondition::all, {}, nullptr, 1, nullptr);
    expect_complete(s.pairs_within(2.5), s.visited(list));
    list.adapt();
    list.invalidate();
    expect_complete(s.pairs_within(2.5), s.visited(list));
}

TEST(VerletList, SmallBoxesWithOneOrTwoCellsPerSide) {
    // 5.2 / (2.5 * 1.02) gives 2 cells per side; 3.0 gives 1 along z.
    System s(120, 5.2, 5.2, 3.0, 6);
    List list(s.backend, 1.4, 1.02, PairCondition::all, {}, nullptr, 1, nullptr);
    expect_complete(s.pairs_within(1.4), s.visited(list));
    System t(60, 5.2, 5.2, 5.2, 7);
    List wide(t.backend, 2.5, 1.02, PairCondition::all, {}, nullptr, 1, nullptr);
    expect_complete(t.pairs_within(2.5), t.visited(wide));
}

TEST(VerletList, CellsHalfTheListRadiusWideWhereEveryAxisHasFiveOrMore) {
    // List radius 2.2: cells 1.1 wide where every axis has more than 4 of them. With exactly 5
    // along x every particle's rows wrap around the box on one side or the other; with 4 along
    // z the grid keeps cells as wide as the list radius (reach 1).
    System s(400, 5.6, 7.0, 9.0, 13);
    List fine(s.backend, 2.0, 1.1, PairCondition::all, {}, nullptr, 1, nullptr);
    expect_complete(s.pairs_within(2.0), s.visited(fine));
    EXPECT_EQ(fine.view().grid.reach, 2);
    EXPECT_EQ(fine.view().grid.nx, 5);
    System t(300, 5.6, 7.0, 4.5, 14);
    List coarse(t.backend, 2.0, 1.1, PairCondition::all, {}, nullptr, 1, nullptr);
    expect_complete(t.pairs_within(2.0), t.visited(coarse));
    EXPECT_EQ(coarse.view().grid.reach, 1);
    EXPECT_EQ(coarse.view().grid.nx, 2);
}

TEST(VerletList, DiluteSystemInALargeBoxKeepsTheGridSmall) {
    System s(50, 400.0, 400.0, 400.0, 8);
    for (int64_t i = 0; i < 10; ++i) s.pos.data()[i] = {0.3 * i, 0.0, 0.0, 0.0};  // a close cluster
    List list(s.backend, 2.5, 1.1, PairCondition::all, {}, nullptr, 1, nullptr);
    expect_complete(s.pairs_within(2.5), s.visited(list));
}

TEST(VerletList, BatchesOverlaidInOneBoxPairOnlyWithinABatch) {
    // Three independent systems in one box: each has cells of its own, so the list holds exactly
    // the pairs within the cutoff and within one batch, after a build and on the cell-scan
    // fallback of overflowing lists (the crowded batch 2).
    System s(900, 12.0, 12.0, 12.0, 12);
    HostBuffer<int> batch;
    s.backend.resize(batch, s.n);
    for (int64_t i = 0; i < s.n; ++i) batch.data()[i] = static_cast<int>(i % 3);
    for (int64_t i = 2; i < s.n; i += 3) {
        Real4<double>& p = s.pos.data()[i];
        p = {0.1 * p.x, 0.1 * p.y, 0.1 * p.z, 0.0};
    }
    List list(s.backend, 2.5, 1.12, PairCondition::all, {}, batch.data(), 3, nullptr);
    std::set<std::pair<int, int>> wanted;
    for (const auto& pair : s.pairs_within(2.5))
        if (batch.data()[pair.first] == batch.data()[pair.second]) wanted.insert(pair);
    const auto seen = s.visited(list);
    expect_complete(wanted, seen);
    for (const auto& pair : seen)
        EXPECT_EQ(batch.data()[pair.first], batch.data()[pair.second])
            << "pair (" << pair.first << ", " << pair.second << ") crosses batches";
    const CellGrid<double>& grid = list.view().grid;
    EXPECT_EQ(grid.batches, 3);
    EXPECT_EQ(grid.count(), 3 * grid.nx * grid.ny * grid.nz);
}

// The cell sorts decode a cell index back into its coordinates (the cell-local positions' packed
// cell, the clusters' sub-cells): coordinates_of inverts index in every batch of an uneven grid.
TEST(CellGrid, CoordinatesOfInvertsIndexInEveryBatch) {
    const Box<double> box = Box<double>::make(11.0, 15.0, 20.0);
    const CellGrid<double> grid = CellGrid<double>::make(box, 2.0, 4000, 3);
    ASSERT_EQ(grid.batches, 3);
    ASSERT_TRUE(grid.nx != grid.ny && grid.ny != grid.nz) << "the axes were meant to differ";
    for (int b = 0; b < grid.batches; ++b)
        for (int cz = 0; cz < grid.nz; ++cz)
            for (int cy = 0; cy < grid.ny; ++cy)
                for (int cx = 0; cx < grid.nx; ++cx) {
                    int x = -1, y = -1, z = -1;
                    grid.coordinates_of(grid.index(cx, cy, cz, b), x, y, z);
                    ASSERT_EQ(x, cx);
                    ASSERT_EQ(y, cy);
                    ASSERT_EQ(z, cz) << "batch " << b;
                }
}

// for_each_run_near() visits a cell exactly where its nearest point lies within the radius of the
// point (the distance measured from the cells' bounds, not through gap()), and each such cell once,
// in runs of consecutive cells of a row (split where a row wraps; runs of one cell where whole runs
// are not asked for) taken in the order of dz, dy, dx; over the points a particle may take, about 21
// of 27 cells at reach 1 and 84 of 125 at reach 2.
template <bool kWholeRuns>
void expect_cells_near_a_point_are_the_ones_the_radius_reaches(int reach, double mostVisited) {
    const Box<double> box = Box<double>::make(14.0, 15.0, 16.0);
    const double radius = 2.8;
    const CellGrid<double> grid = CellGrid<double>::make(box, radius, 3000, 1, reach);
    ASSERT_EQ(grid.reach, reach);
    const Vec3<double> width{box.length.x / grid.nx, box.length.y / grid.ny, box.length.z / grid.nz};
    std::mt19937 random(21);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    long visitedCells = 0, points = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const Vec3<double> u{uniform(random) * grid.nx, uniform(random) * grid.ny, uniform(random) * grid.nz};
        const int cx = static_cast<int>(u.x), cy = static_cast<int>(u.y), cz = static_cast<int>(u.z);
        std::map<int, int> visits;
        std::vector<std::array<int, 3>> offsets;  // of the cells in the order visited
        grid.for_each_run_near<kWholeRuns>(u, cx, cy, cz, 0, radius * radius, [&](int first, int last, int dx, int dy, int dz) {
            ASSERT_LE(first, last);
            if (!kWholeRuns) ASSERT_EQ(first, last) << "cells one by one";
            ASSERT_EQ(first / grid.nx, last / grid.nx) << "a run lies in one row";
            for (int c = first; c <= last; ++c) {
                const int offset = dx + (c - first);
                const int named = grid.index(CellGrid<double>::periodic(cx + offset, grid.nx),
                                             CellGrid<double>::periodic(cy + dy, grid.ny),
                                             CellGrid<double>::periodic(cz + dz, grid.nz));
                EXPECT_EQ(c, named) << "the offsets name the cell";
                ++visits[c];
                offsets.push_back({dz, dy, offset});
            }
        });
        EXPECT_TRUE(std::is_sorted(offsets.begin(), offsets.end())) << "cells in the order of dz, dy, dx";
        for (int dz = -reach; dz <= reach; ++dz)
            for (int dy = -reach; dy <= reach; ++dy)
                for (int dx = -reach; dx <= reach; ++dx) {
                    // The point of cell (cx + dx, ...) nearest u, along each axis, in length units.
                    const auto nearest = [](double at, int c, int offset, double w) {
                        const double low = (c + offset) * w, high = low + w;
                        return at * w < low ? low - at * w : (at * w > high ? at * w - high : 0.0);
                    };
                    const double gx = nearest(u.x, cx, dx, width.x), gy = nearest(u.y, cy, dy, width.y),
                                 gz = nearest(u.z, cz, dz, width.z);
                    const bool reached = gx * gx + gy * gy + gz * gz < radius * radius;
                    const int cell = grid.index(CellGrid<double>::periodic(cx + dx, grid.nx),
                                                CellGrid<double>::periodic(cy + dy, grid.ny),
                                                CellGrid<double>::periodic(cz + dz, grid.nz));
                    const auto found = visits.find(cell);
                    ASSERT_EQ(found != visits.end(), reached) << "offset " << dx << " " << dy << " " << dz;
                    if (reached) ASSERT_EQ(found->second, 1);
                }
        visitedCells += static_cast<long>(visits.size());
        ++points;
    }
    const double stencil = (2 * reach + 1) * (2 * reach + 1) * (2 * reach + 1);
    EXPECT_LT(visitedCells, mostVisited * stencil * points) << "cells out of reach are skipped";
    EXPECT_GT(visitedCells, 0.5 * stencil * points);
}

TEST(CellGrid, CellsNearAPointAreTheOnesTheRadiusReaches) {
    for (const bool wholeRuns : {true, false}) {
        SCOPED_TRACE(wholeRuns ? "whole runs" : "cells one by one");
        const auto expect = wholeRuns ? expect_cells_near_a_point_are_the_ones_the_radius_reaches<true>
                                      : expect_cells_near_a_point_are_the_ones_the_radius_reaches<false>;
        expect(1, 0.85);
        expect(2, 0.75);
    }
}

TEST(VerletList, SlotsAreAPermutationInCellOrder) {
    System s(900, 11.0, 12.0, 13.0, 9);
    List list(s.backend, 2.5, 1.12, PairCondition::all, {}, nullptr, 1, nullptr);
    s.visited(list);
    const NeighbourView<double> view = list.view();
    std::vector<int> seen(s.n, 0);
    int previousCell = -1, previousParticle = -1;
    for (int64_t k = 0; k < s.n; ++k) {
        const int i = view.order[k];
        ASSERT_GE(i, 0);
        ASSERT_LT(i, s.n);
        ++seen[i];
        int cx, cy, cz;
        view.grid.coordinates(xyz(s.pos.data()[i]), s.box, cx, cy, cz);
        const int cell = view.grid.index(cx, cy, cz);
        EXPECT_GE(k, view.cellStart[cell]) << "particle " << i << " lies outside its cell's slots";
        EXPECT_LT(k, view.cellStart[cell + 1]) << "particle " << i << " lies outside its cell's slots";
        EXPECT_GE(cell, previousCell) << "slots are not in cell order";
        if (cell == previousCell) EXPECT_GT(i, previousParticle) << "a cell's slots are not in particle order";
        previousCell = cell;
        previousParticle = i;
    }
    for (int64_t i = 0; i < s.n; ++i) EXPECT_EQ(seen[i], 1) << "particle " << i;
    EXPECT_EQ(view.cellStart[view.grid.count()], s.n);
}

TEST(VerletList, CompleteWithAGridScannedInChunks) {
    // 21^3 cells (on the CPU half the list radius wide, 34 a side, then thinned to about twice the
    // particles), whose counts are scanned in 73 chunks of 128 cells: the chunks before a cell must
    // all be counted for its first slot to be right.
    System s(6000, 19.0, 19.0, 19.0, 11);
    List list(s.backend, 1.0, 1.1, PairCondition::all, {}, nullptr, 1, nullptr);
    expect_complete(s.pairs_within(1.0), s.visited(list));
    EXPECT_EQ(list.view().grid.count(), 21 * 21 * 21);
    EXPECT_EQ(list.view().grid.reach, 2);
    EXPECT_EQ(list.view().cellStart[list.view().grid.count()], s.n);
}

TEST(VerletList, SameSlotsAndListsOnOneThreadAndOnFour) {
    // Enough particles that the CPU backend's loops run in parallel (kParallelThreshold).
    System one(6000, 19.0, 19.0, 19.0, 10, 1);
    System four(6000, 19.0, 19.0, 19.0, 10, 4);
    List a(one.backend, 2.5, 1.12, PairCondition::all, {}, nullptr, 1, nullptr);
    List b(four.backend, 2.5, 1.12, PairCondition::all, {}, nullptr, 1, nullptr);
    for (int round = 0; round < 3; ++round) {
        const auto x = one.slots_and_lists(a);
        const auto y = four.slots_and_lists(b);
        EXPECT_EQ(x.first, y.first) << "round " << round;
        EXPECT_EQ(x.second, y.second) << "round " << round;
        for (const auto& entries : x.second)
            EXPECT_TRUE(std::is_sorted(entries.begin(), entries.end())) << "the CPU's lists run in particle order";
        one.jiggle(0.4, 20 + round);  // past half the skin: every round rebuilds
        four.jiggle(0.4, 20 + round);
    }
}

// How the GPU lays out a list: by columns of chunks (one thread a particle) or by rows (several
// lanes a particle, below some 270,000 particles).
enum class GpuLayout { kColumns, kRows };

// The build loop a GPU runs (the BuildListsAlong with_build_path chooses, one slot at a time with
// one lane, writing its lists by columns of chunks as a GPU thread per particle does, or by rows)
// against the CPU's row pass that built the list, both read through for_each_neighbour: the same
// slots in every list, each once, for each way of taking separations (the minimum image, the image
// of the candidate's cell, or cell-local positions) and each filter (any pair, or exclusions). A pair
// on which they differ may only be one the two roundings put on either side of the list radius.
// Where the list keeps cell-local positions its entries carry the cells' offset, as the GPU's do;
// with `forcesOfSigma`, a mixed-precision pair kernel over them also sums the forces it sums over
// the CPU rows' slots: LJ of that sigma, for a configuration without overlaps (its forces bounded).
template <class Configure>
void expect_gpu_loop_lists_what_rows_list(System& s, Configure configure, const PairFilterInputs& inputs,
                                          bool cellLocal, bool imagesByOffset, double forcesOfSigma = 0.0,
                                          GpuLayout layout = GpuLayout::kColumns) {
    List list(s.backend, 2.5, 1.12, PairCondition::all, inputs, nullptr, 1, nullptr);
    configure(list);
    list.update(s.pos, s.n, s.box, ++s.version);
    NeighbourView<double> v = list.view();
    ASSERT_EQ(v.cellLocal.local != nullptr, cellLocal);
    ASSERT_EQ(v.grid.images_by_offset(), imagesByOffset);
    ASSERT_EQ(v.filter.trivial(), inputs.excluded.empty());
    ASSERT_EQ(v.capacity % NeighbourView<double>::kChunk, 0) << "a list holds whole chunks";
    ASSERT_EQ(v.entryShift, 0) << "the CPU's lists carry slots alone";
    ASSERT_TRUE(v.by_rows());
    const NeighbourView<double> rows = v;
    // The GPU loop's lists in the layout asked for (rows: the CPU's own strides), read back through
    // the view's own traversal.
    if (layout == GpuLayout::kColumns) {
        v.particleStride = NeighbourView<double>::kChunk;
        v.chunkStride = NeighbourView<double>::kChunk * s.n;
    }
    if (cellLocal) v.entryShift = CellLocalPositions<double>::kOffsetBits;  // as the GPU's lists carry
    std::vector<int> entries(static_cast<size_t>(v.capacity) * s.n), counts(s.n);
    v.list = entries.data();
    v.count = counts.data();
    int control[kControlSlots] = {};
    control[kRebuild] = 1;
    const double radius = 2.5 + list.skin();
    const BuildLists<double> lists{v, radius * radius, control, false};
    with_build_path(lists, [&](const auto& along) {
        for (int64_t k = 0; k < s.n; ++k) along(k, Lanes{});
    });
    int64_t listed = 0, borderline = 0;
    for (int64_t k = 0; k < s.n; ++k) {
        ASSERT_LE(counts[k], v.capacity) << "slot " << k << " overflowed";
        std::set<int> mine, theirs;
        v.for_each_neighbour(static_cast<int>(k), [&](int t) { EXPECT_TRUE(mine.insert(t).second) << "slot " << k; });
        if (cellLocal) {
            // The cells' offset an entry carries gives the separation the cells' codes give, bit for bit.
            const CellLocalPositions<double>& local = v.cellLocal;
            v.for_each_entry(static_cast<int>(k), [&](int entry) {
                const int t = CellLocalPositions<double>::slot_of_entry(entry);
                const Vec3<float> byEntry = local.separation(local.local[k], local.local[t], entry);
                const Vec3<float> byCodes = local.separation(local.local[k], local.local[t]);
                EXPECT_EQ(byEntry.x, byCodes.x) << "slot " << k << " and " << t;
                EXPECT_EQ(byEntry.y, byCodes.y) << "slot " << k << " and " << t;
                EXPECT_EQ(byEntry.z, byCodes.z) << "slot " << k << " and " << t;
            }, [&](int) { ADD_FAILURE() << "slot " << k << " overflowed"; });
        }
        if (layout == GpuLayout::kRows) {
            // Shared out among four lanes, as the GPU's readers of rows take them: each entry once.
            std::multiset<int> shared;
            for (int lane = 0; lane < 4; ++lane) {
                Lanes lanes;
                lanes.count = 4;
                lanes.lane = lane;
                v.for_each_neighbour(static_cast<int>(k), [&](int t) { shared.insert(t); }, lanes);
            }
            EXPECT_EQ(std::set<int>(shared.begin(), shared.end()), mine) << "slot " << k;
            EXPECT_EQ(shared.size(), mine.size()) << "slot " << k;
        }
        EXPECT_EQ(static_cast<int>(mine.size()), counts[k]) << "slot " << k;
        rows.for_each_neighbour(static_cast<int>(k), [&](int t) { theirs.insert(t); });
        listed += static_cast<int64_t>(theirs.size());
        std::vector<int> differing;
        std::set_symmetric_difference(mine.begin(), mine.end(), theirs.begin(), theirs.end(),
                                      std::back_inserter(differing));
        for (int t : differing) {
            const Vec3<double> d = s.box.minimum_image(xyz(v.positions[t]) - xyz(v.positions[k]));
            EXPECT_NEAR(std::sqrt(dot(d, d)), radius, 1e-5) << "slot " << k << " and " << t << " listed by one loop only";
            ++borderline;
        }
    }
    EXPECT_GT(listed, 20 * s.n) << "the lists were meant to hold a liquid's neighbours";
    EXPECT_LE(borderline, 2);
    if (!(forcesOfSigma > 0.0)) return;
    ASSERT_TRUE(cellLocal);
    using LJ = LennardJonesType1;
    const LJ::Params<float> params = LJ::make_pair_params<float>(1.0, forcesOfSigma, 2.5 * forcesOfSigma, false);
    const auto forces_over = [&](const NeighbourView<double>& view) {
        std::vector<Real4<double>> force(s.n, Real4<double>{0, 0, 0, 0});
        PairKernel<LJ, double, float, true, false, false> kernel{nullptr, nullptr, nullptr, view, {&params, 1, nullptr}, {}};
        kernel.out.force = force.data();
        for (int64_t k = 0; k < s.n; ++k) kernel(k, Lanes{});
        return force;
    };
    const std::vector<Real4<double>> byEntries = forces_over(v), byCodes = forces_over(rows);
    double largest = 0.0, deviation = 0.0;
    for (int64_t k = 0; k < s.n; ++k) {
        largest = std::max({largest, std::abs(byCodes[k].x), std::abs(byCodes[k].y), std::abs(byCodes[k].z)});
        deviation = std::max({deviation, std::abs(byEntries[k].x - byCodes[k].x), std::abs(byEntries[k].y - byCodes[k].y),
                              std::abs(byEntries[k].z - byCodes[k].z)});
    }
    ASSERT_GT(largest, 10.0) << "the configuration was meant to have forces";
    // The same separations bit for bit (above): the sums differ in order alone.
    EXPECT_LT(deviation, 1e-5 * largest);
}

// Each particle excludes the `reach` before and after it: a filter that is not trivial. A reach of 1
// or 2 leaves a particle few enough exclusions to hold in registers, 3 too many
// (PairFilter::FewExclusions).
PairFilterInputs exclusions_of_neighbours_in_id(int64_t n, int64_t reach = 3) {
    PairFilterInputs inputs;
    inputs.excluded.resize(n);
    for (int64_t i = 0; i < n; ++i)
        for (int64_t j = i - reach; j <= i + reach; ++j)
            if (j != i && j >= 0 && j < n) inputs.excluded[i].push_back(static_cast<int>(j));
    return inputs;
}

// A particle's exclusions held in registers (up to four) or searched (more) judge every pair as the
// search alone does, and the list's condition still applies.
TEST(PairFilter, FewExclusionsJudgeAsTheSearchDoes) {
    constexpr int n = 40;
    std::vector<int> start{0}, excluded, model(n);
    for (int i = 0; i < n; ++i) {
        model[i] = i % 3;
        for (int j = 0; j < i % 7; ++j) excluded.push_back((i + 5 * j + 1) % n);  // 0 to 6 exclusions, distinct
        std::sort(excluded.begin() + start.back(), excluded.end());
        start.push_back(static_cast<int>(excluded.size()));
    }
    for (const PairCondition condition : {PairCondition::all, PairCondition::intra}) {
        PairFilter filter;
        filter.condition = condition;
        filter.model = model.data();
        filter.excludedStart = start.data();
        filter.excluded = excluded.data();
        int rejected = 0;
        for (int i = 0; i < n; ++i) {
            const PairFilter::FewExclusions few = filter.few_exclusions_of(i);
            EXPECT_EQ(few.many, i % 7 > PairFilter::FewExclusions::kMost) << "particle " << i;
            for (int j = 0; j < n; ++j) {
                EXPECT_EQ(filter.accepts(i, j, few), filter.accepts(i, j)) << "pair " << i << " " << j;
                rejected += !filter.accepts(i, j, few);
            }
        }
        if (condition == PairCondition::all) EXPECT_EQ(rejected, static_cast<int>(excluded.size()));
    }
}

TEST(VerletList, GpuBuildLoopListsWhatTheCpuRowsList) {
    const auto asIs = [](List&) {};
    const auto keepCellLocal = [](List& list) { list.keep_cell_local_positions(); };
    // Cells 1.4 wide, 10 or 11 along each axis (reach 2): images by the cells' offsets.
    System wide(3000, 14.0, 15.0, 16.0, 12);
    const PairFilterInputs wideExclusions = exclusions_of_neighbours_in_id(wide.n);
    expect_gpu_loop_lists_what_rows_list(wide, asIs, {}, false, true);
    expect_gpu_loop_lists_what_rows_list(wide, asIs, wideExclusions, false, true);
    expect_gpu_loop_lists_what_rows_list(wide, keepCellLocal, {}, true, true);
    expect_gpu_loop_lists_what_rows_list(wide, keepCellLocal, wideExclusions, true, true);
    expect_gpu_loop_lists_what_rows_list(wide, asIs, exclusions_of_neighbours_in_id(wide.n, 1), false, true);
    expect_gpu_loop_lists_what_rows_list(wide, keepCellLocal, exclusions_of_neighbours_in_id(wide.n, 2), true, true);
    // Five cells along each axis (reach 2): a cell across the boundary may be nearer than L / 2,
    // so the loop takes the minimum image.
    System narrow(430, 8.0, 8.0, 8.0, 13);
    const PairFilterInputs narrowExclusions = exclusions_of_neighbours_in_id(narrow.n);
    expect_gpu_loop_lists_what_rows_list(narrow, asIs, {}, false, false);
    expect_gpu_loop_lists_what_rows_list(narrow, asIs, narrowExclusions, false, false);
    expect_gpu_loop_lists_what_rows_list(narrow, keepCellLocal, {}, true, false);
}

// The mixed-precision pair kernel over entries that carry their cells' offset, on a liquid-like
// lattice of 27,000 (about 21 cells along each axis), against the same kernel over the CPU rows'
// slots: the GPU's columns, and its rows (several lanes a particle) with and without exclusions.
TEST(VerletList, GpuBuildLoopEntriesGiveTheForcesOfTheCellCodes) {
    System lattice(27000, 30.0, 30.0, 30.0, 14);
    lattice.place_on_jittered_lattice(1.0);
    const auto keepCellLocal = [](List& list) { list.keep_cell_local_positions(); };
    expect_gpu_loop_lists_what_rows_list(lattice, keepCellLocal, {}, true, true, 1.0, GpuLayout::kColumns);
    expect_gpu_loop_lists_what_rows_list(lattice, keepCellLocal, {}, true, true, 1.0, GpuLayout::kRows);
    // With exclusions: the filter's path writes the offsets too.
    expect_gpu_loop_lists_what_rows_list(lattice, keepCellLocal, exclusions_of_neighbours_in_id(lattice.n), true, true,
                                         1.0, GpuLayout::kRows);
}

}  // namespace
}  // namespace structmd
