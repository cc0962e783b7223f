// Cell-local positions (state/cell_local_positions.hpp): a list that keeps them gives, for every
// listed pair, the separation of the double positions to within the rounding of a cell's width,
// after builds, after moves under half the skin and across the periodic boundary; the
// mixed-precision pair kernel over them agrees with the double one, within a few times the rounding
// of separations taken in double; the cells' codes give every neighbouring cells' distance up to the
// largest grid they fit; a grid they do not fit leaves them out; and the list's positions
// in slot order are copied each step only once some caller reads them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "forcefield/lennard_jones.hpp"
#include "forcefield/pair_kernel.hpp"
#include "neighbour/verlet_list.hpp"
#include "random_particles.hpp"

namespace structmd {
namespace {

using List = VerletList<CpuBackend, double>;

// The largest difference, over every listed pair, between the cell-local separation and the
// minimum image of the double positions.
double largest_separation_error(List& list, RandomParticles& s) {
    list.update(s.pos, s.n, s.box, ++s.version);
    const NeighbourView<double> v = list.view();
    EXPECT_NE(v.cellLocal.local, nullptr) << "the list was meant to keep cell-local positions";
    if (!v.cellLocal.local) return INFINITY;
    double largest = 0.0;
    int64_t pairs = 0;
    for (int k = 0; k < s.n; ++k)
        v.for_each_neighbour(k, [&](int t) {
            const Vec3<float> local = v.cellLocal.separation(v.cellLocal.local[k], v.cellLocal.local[t]);
            const Vec3<double> exact = s.box.minimum_image(xyz(v.positions[t]) - xyz(v.positions[k]));
            largest = std::max({largest, std::abs(local.x - exact.x), std::abs(local.y - exact.y),
                                std::abs(local.z - exact.z)});
            ++pairs;
        });
    EXPECT_GT(pairs, 20 * s.n) << "the list was meant to hold a liquid's neighbours";
    return largest;
}

// A box 120 long: an absolute position in float would be rounded by up to ulp(60) / 2 = 3.8e-6, so
// the separations would be off by several 1e-6. Relative to cells 1.4 wide (the CPU's half-width
// cells) the rounding is a few 1e-8, and the cells' distances are exact multiples of a float width.
TEST(CellLocalPositions, SeparationsMatchTheDoublePositionsAcrossTheBoundary) {
    RandomParticles s(120 * 12 * 12, 120.0, 12.0, 12.0, 3);
    s.place_on_jittered_lattice(1.0);
    List list(s.backend, 2.5, 1.12, PairCondition::all, {}, nullptr, 1, nullptr);
    list.keep_cell_local_positions();
    EXPECT_LT(largest_separation_error(list, s), 4e-7);
    // Moves under half the skin (no build): the positions are refreshed relative to the same cells,
    // some of them across the periodic boundary.
    for (int k = 0; k < 3; ++k) {
        s.jiggle(0.045, 30 + k);
        EXPECT_LT(largest_separation_error(list, s), 4e-7);
    }
    list.adapt();
    EXPECT_EQ(list.builds(), 1);
    s.jiggle(0.2, 40);  // over half the skin: a build, with new cells
    EXPECT_LT(largest_separation_error(list, s), 4e-7);
    list.adapt();
    EXPECT_EQ(list.builds(), 2);
}

// The mixed-precision kernel (double positions and sums, float potential) over cell-local positions
// against the double kernel, in a box 100 long.
TEST(CellLocalPositions, MixedPairKernelAgreesWithDouble) {
    RandomParticles s(100 * 11 * 11, 100.0, 11.0, 11.0, 4);
    s.place_on_jittered_lattice(1.0);
    using LJ = LennardJonesType1;
    const auto table_in = [](auto real) {
        using T = decltype(real);
        std::vector<LJ::Params<T>> table;
        for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b)
                table.push_back(LJ::make_pair_params<T>(1.0 + 0.2 * (a + b), 1.0 + 0.05 * (a + b), 2.5, true));
        return table;
    };
    HostBuffer<LJ::Params<double>> doubles;
    HostBuffer<LJ::Params<float>> floats;
    s.backend.upload(doubles, table_in(0.0).data(), 4);
    s.backend.upload(floats, table_in(0.0f).data(), 4);
    struct Result {
        std::vector<Real4<double>> force;
        std::vector<double> energy;
        std::vector<Tensor3<double>> virial;
    };
    // perSlot: the kernel's own per-slot path, the one the GPU runs (float lane sums), instead of the
    // CPU's row pass.
    const auto run = [&](auto kernel, bool keep, bool perSlot = false) {
        List list(s.backend, 2.5, 1.12, PairCondition::all, {}, nullptr, 1, nullptr);
        if (keep) list.keep_cell_local_positions();
        list.update(s.pos, s.n, s.box, 1);
        EXPECT_EQ(list.view().cellLocal.local != nullptr, keep);
        Result r{std::vector<Real4<double>>(s.n, Real4<double>{0, 0, 0, 0}), std::vector<double>(s.n, 0.0),
                 std::vector<Tensor3<double>>(s.n, zero_tensor<double>())};
        kernel.neighbours = list.view();
        kernel.out.force = r.force.data();
        kernel.out.energy = r.energy.data();
        kernel.out.virial = r.virial.data();
        if (perSlot)
            for (int64_t k = 0; k < s.n; ++k) kernel(k, Lanes{});
        else
            s.backend.for_each_lanes(s.n, kernel);
        return r;
    };
    const Result reference =
        run(PairKernel<LJ, double, double, true, true, true>{nullptr, nullptr, nullptr, {}, {doubles.data(), 2, nullptr}, {}},
            false);
    const Result mixed =
        run(PairKernel<LJ, double, float, true, true, true>{nullptr, nullptr, nullptr, {}, {floats.data(), 2, nullptr}, {}},
            true);
    const Result mixedPerSlot =
        run(PairKernel<LJ, double, float, true, true, true>{nullptr, nullptr, nullptr, {}, {floats.data(), 2, nullptr}, {}},
            true, true);
    // The same float potential over separations taken in double: the rounding mixed precision
    // had before cell-local positions.
    const Result doubleSeparations =
        run(PairKernel<LJ, double, float, true, true, true>{nullptr, nullptr, nullptr, {}, {floats.data(), 2, nullptr}, {}},
            false);
    double largestForce = 0.0;
    for (int64_t i = 0; i < s.n; ++i)
        largestForce = std::max({largestForce, std::abs(reference.force[i].x), std::abs(reference.force[i].y)});
    ASSERT_GT(largestForce, 10.0) << "the configuration was meant to have forces";
    struct Deviation {
        double force = 0.0, energy = 0.0, virial = 0.0;
    };
    const auto deviation = [&](const Result& r) {
        Deviation d;
        for (int64_t i = 0; i < s.n; ++i) {
            d.force = std::max({d.force, std::abs(r.force[i].x - reference.force[i].x),
                                std::abs(r.force[i].y - reference.force[i].y),
                                std::abs(r.force[i].z - reference.force[i].z)});
            d.energy = std::max(d.energy, std::abs(r.energy[i] - reference.energy[i]));
            d.virial = std::max({d.virial, std::abs(r.virial[i].xx - reference.virial[i].xx),
                                 std::abs(r.virial[i].yz - reference.virial[i].yz)});
        }
        return d;
    };
    const Deviation local = deviation(mixed), perSlot = deviation(mixedPerSlot), before = deviation(doubleSeparations);
    std::printf("[ deviation ] largest force %.1f; cell-local: force %.2e energy %.2e virial %.2e; "
                "double separations: force %.2e energy %.2e virial %.2e\n",
                largestForce, local.force, local.energy, local.virial, before.force, before.energy, before.virial);
    // Pairs here come as close as 0.75 sigma, where the force is steepest (r^-14): a separation off
    // by 1e-7 (the float rounding of the two local positions and of their difference) moves it by
    // 2e-6 of itself, three times the double separations' rounding of r^2 alone. Absolute positions
    // in float, off by ulp(50) / 2 = 1.9e-6 each, would move it by about 5e-5.
    EXPECT_LT(local.force, 3e-6 * largestForce);
    EXPECT_LT(local.force, 4.0 * before.force);
    EXPECT_LT(local.energy, 4.0 * before.energy);
    EXPECT_LT(local.virial, 4.0 * before.virial);
    // The per-slot path sums each lane's force in float: the same bounds.
    std::printf("[ deviation ] per slot: force %.2e energy %.2e virial %.2e\n", perSlot.force, perSlot.energy,
                perSlot.virial);
    EXPECT_LT(perSlot.force, 3e-6 * largestForce);
    EXPECT_LT(perSlot.force, 4.0 * before.force);
    EXPECT_LT(perSlot.energy, 4.0 * before.energy);
    EXPECT_LT(perSlot.virial, 4.0 * before.virial);
}

// The list's copy of the positions in slot order is left to the builds while only cell-local pair
// kernels read the list (cell_local_view(): the types alone, which a build sets), so a drift writes
// the cell-local positions alone; the first view() copies the positions and the mirror keeps them
// from then on, also where that view() came between a drift's arming and its run.
TEST(CellLocalPositions, SlotPositionsKeptOnlyOnceSomeCallerReadsThem) {
    RandomParticles s(20 * 12 * 12, 20.0, 12.0, 12.0, 6);
    s.place_on_jittered_lattice(1.0);
    List list(s.backend, 2.5, 1.12, PairCondition::all, {}, nullptr, 1, nullptr);
    list.keep_cell_local_positions();
    const auto slots_hold_positions = [&](const NeighbourView<double>& v) {
        int64_t same = 0;
        for (int k = 0; k < s.n; ++k) {
            const Real4<double>& p = s.pos.data()[v.order[k]];
            same += v.positions[k].x == p.x && v.positions[k].y == p.y && v.positions[k].z == p.z;
            EXPECT_EQ(v.positions[k].w, p.w) << "slot " << k << ": the type a cell-local kernel reads";
        }
        return same == s.n;
    };
    // The cell-local positions follow the moves whether or not the slots' positions do.
    const auto cell_local_current = [&](const NeighbourView<double>& v) {
        double largest = 0.0;
        for (int k = 0; k < s.n; ++k)
            v.for_each_neighbour(k, [&](int t) {
                const Vec3<float> local = v.cellLocal.separation(v.cellLocal.local[k], v.cellLocal.local[t]);
                const Vec3<double> exact =
                    s.box.minimum_image(xyz(s.pos.data()[v.order[t]]) - xyz(s.pos.data()[v.order[k]]));
                largest = std::max({largest, std::abs(local.x - exact.x), std::abs(local.y - exact.y),
                                    std::abs(local.z - exact.z)});
            });
        return largest < 4e-7;
    };
    // A drift under half the skin with the bookkeeping `armed` (state/drift_bookkeeping.hpp), then
    // the list brought up to date as the engine's next force evaluation does.
    const auto drift = [&](const SlotMirror<double>& armed, unsigned seed) {
        const int* slotOf = list.slot_of(s.pos.data(), s.n);
        ASSERT_NE(slotOf, nullptr);
        s.jiggle(0.045, seed);
        ++s.version;
        for (int64_t i = 0; i < s.n; ++i) armed.record(slotOf[i], s.pos.data()[i]);
        list.mirrored(s.version, armed.positions != nullptr);
        list.update(s.pos, s.n, s.box, s.version);
    };
    list.update(s.pos, s.n, s.box, ++s.version);  // the build copies every slot's position
    EXPECT_TRUE(slots_hold_positions(list.cell_local_view()));
    EXPECT_EQ(list.mirror().positions, nullptr);
    drift(list.mirror(), 50);
    EXPECT_FALSE(slots_hold_positions(list.cell_local_view()));
    EXPECT_TRUE(cell_local_current(list.cell_local_view()));
    const SlotMirror<double> armedBeforeTheView = list.mirror();
    EXPECT_TRUE(slots_hold_positions(list.view()));  // copied for the caller that reads them
    EXPECT_NE(list.mirror().positions, nullptr);
    drift(armedBeforeTheView, 51);  // without the positions: the update copies them
    EXPECT_TRUE(slots_hold_positions(list.cell_local_view()));
    drift(list.mirror(), 52);  // with them
    EXPECT_TRUE(slots_hold_positions(list.cell_local_view()));
    EXPECT_TRUE(cell_local_current(list.cell_local_view()));
    list.adapt();
    EXPECT_EQ(list.builds(), 1);
}

// The cells' codes, up to the largest grid whose codes a float holds: for every pair of cells within
// reach of each other (across the periodic boundary too), separation() adds the cells' distance
// that the double positions have, whichever cell of the grid the pair sits in. Digits of the
// codes: a power of two of at least twice the cells along x and y.
TEST(CellLocalPositions, CellCodesSplitIntoEveryNeighbouringCellsDistance) {
    EXPECT_EQ(CellLocalPositions<double>::digit_bits(5), 4);
    EXPECT_EQ(CellLocalPositions<double>::digit_bits(8), 4);
    EXPECT_EQ(CellLocalPositions<double>::digit_bits(9), 5);
    EXPECT_TRUE(CellLocalPositions<double>::codes_fit(128, 128, 256));   // 2^8 2^8 256 = 2^24
    EXPECT_FALSE(CellLocalPositions<double>::codes_fit(128, 128, 257));
    EXPECT_FALSE(CellLocalPositions<double>::codes_fit(129, 128, 256));  // x's digit 2^9
    EXPECT_TRUE(CellLocalPositions<double>::codes_fit(60, 60, 60));      // 4M LJ particles
    struct Grid {
        int nx, ny, nz, reach;
    };
    for (const Grid& g : {Grid{5, 6, 7, 2}, Grid{3, 4, 3, 1}, Grid{128, 97, 256, 1}, Grid{100, 128, 255, 2}}) {
        ASSERT_TRUE(CellLocalPositions<double>::codes_fit(g.nx, g.ny, g.nz));
        const double edge = 1.3;
        const Box<double> box = Box<double>::make(g.nx * edge, g.ny * edge, g.nz * edge);
        CellLocalPositions<double> local;
        local.set_width({edge, edge, edge});
        local.halfLength = {0.5 * box.length.x, 0.5 * box.length.y, 0.5 * box.length.z};
        local.set_cells(g.nx, g.ny, g.nz);
        // The cells of a row along each axis that reach the boundary, and some inside.
        const auto cells_along = [&](int n) {
            std::vector<int> c{0, 1, n / 2, n - 2, n - 1};
            if (g.reach == 2) c.push_back(2);
            return c;
        };
        const auto centre = [&](int cx, int cy, int cz) {
            return Vec3<double>{(cx + 0.5) * edge - local.halfLength.x, (cy + 0.5) * edge - local.halfLength.y,
                                (cz + 0.5) * edge - local.halfLength.z};
        };
        double largest = 0.0;
        int pairs = 0;
        for (int ax : cells_along(g.nx))
            for (int ay : cells_along(g.ny))
                for (int az : cells_along(g.nz))
                    for (int dx = -g.reach; dx <= g.reach; ++dx)
                        for (int dy = -g.reach; dy <= g.reach; ++dy)
                            for (int dz = -g.reach; dz <= g.reach; ++dz) {
                                const int bx = (ax + dx + g.nx) % g.nx, by = (ay + dy + g.ny) % g.ny,
                                          bz = (az + dz + g.nz) % g.nz;
                                // Positions off their cells' centres, less than half the box apart
                                // (as a listed pair is) on the smallest grid.
                                const Vec3<double> xa = centre(ax, ay, az) + Vec3<double>{0.21, -0.27, 0.17};
                                const Vec3<double> xb = centre(bx, by, bz) + Vec3<double>{-0.23, 0.25, -0.29};
                                const Real4<float> la = local.of(xa, local.pack(ax, ay, az), box);
                                const Real4<float> lb = local.of(xb, local.pack(bx, by, bz), box);
                                const Vec3<float> d = local.separation(la, lb);
                                const Vec3<double> exact = box.minimum_image(xb - xa);
                                largest = std::max({largest, std::abs(d.x - exact.x), std::abs(d.y - exact.y),
                                                    std::abs(d.z - exact.z)});
                                ++pairs;
                            }
        EXPECT_LT(largest, 1e-6) << g.nx << " x " << g.ny << " x " << g.nz << " cells, reach " << g.reach;
        EXPECT_GT(pairs, 1000);
    }
}

// Where the cells' distances cannot be folded once (too few cells along an axis) or an axis is
// open, the list keeps no cell-local positions and the kernels take the double ones.
TEST(CellLocalPositions, LeftOutWhereTheGridCannotFoldTheCells) {
    for (const Vec3<double>& length : {Vec3<double>{6.0, 20.0, 20.0}, Vec3<double>{20.0, 20.0, kOpenAxis}}) {
        RandomParticles s(400, length.x, length.y, std::isinf(length.z) ? 20.0 : length.z, 5);
        s.box = Box<double>::make(length.x, length.y, length.z);
        List list(s.backend, 2.5, 1.12, PairCondition::all, {}, nullptr, 1, nullptr);
        list.keep_cell_local_positions();
        list.update(s.pos, s.n, s.box, 1);
        EXPECT_EQ(list.view().cellLocal.local, nullptr) << "box " << length.x << " x " << length.y << " x " << length.z;
        EXPECT_EQ(list.mirror().cellLocal.local, nullptr);
    }
}

}  // namespace
}  // namespace structmd
