// The slab domains' one rule (core/slab_geometry.hpp), which the host and a domain's engine both
// apply: who owns a coordinate, where an owned particle goes at a rebuild, which faces it borders;
// and the backend's select, which a rebuild sorts the slots with.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "backends/cpu/cpu_backend.hpp"
#include "core/slab_geometry.hpp"

namespace structmd {
namespace {

SlabGeometry slabs(int ranks, int rank, double length = 12.0, double width = 1.0) {
    SlabGeometry g;
    g.length = length;
    g.ranks = ranks;
    g.rank = rank;
    g.width = width;
    return g;
}

TEST(SlabGeometry, OwnerFollowsThePeriodicCoordinate) {
    const SlabGeometry g = slabs(4, 0);  // slabs of 3
    EXPECT_EQ(g.slab_of(0.0), 0);
    EXPECT_EQ(g.slab_of(2.999), 0);
    EXPECT_EQ(g.slab_of(3.0), 1);
    EXPECT_EQ(g.slab_of(11.999), 3);
    EXPECT_EQ(g.slab_of(12.0), 0);   // the box's far face is its near one
    EXPECT_EQ(g.slab_of(-0.5), 3);   // an image below the box
    EXPECT_EQ(g.slab_of(13.5), 0);   // and above it
    EXPECT_EQ(g.slab_of(-1e-17), 0);  // a fraction that rounds to 1 is 0
}

TEST(SlabGeometry, DestinationIsTheNeighbourCrossedInto) {
    const SlabGeometry g = slabs(4, 1);  // owns [3, 6)
    EXPECT_EQ(g.destination(4.0), SlabGeometry::kStays);
    EXPECT_EQ(g.destination(6.1), SlabGeometry::kUp);
    EXPECT_EQ(g.destination(2.9), SlabGeometry::kDown);
    EXPECT_EQ(g.destination(10.0), SlabGeometry::kAstray);
    // The last slab's up neighbour is the first, across the periodic boundary.
    const SlabGeometry last = slabs(4, 3);
    EXPECT_EQ(last.destination(0.5), SlabGeometry::kUp);
    EXPECT_EQ(last.destination(8.5), SlabGeometry::kDown);
    // Two ranks: both neighbours are the other rank, reached by the one link up.
    const SlabGeometry two = slabs(2, 0);
    EXPECT_EQ(two.destination(7.0), SlabGeometry::kUp);
    EXPECT_EQ(two.destination(-1.0), SlabGeometry::kUp);
}

TEST(SlabGeometry, BordersAreTheFacesWithinTheGhostWidth) {
    const SlabGeometry g = slabs(4, 1, 12.0, 1.0);  // owns [3, 6): upper face at 6, lower at 3
    EXPECT_EQ(g.links(), 2);
    EXPECT_EQ(g.borders(4.5), 0);
    EXPECT_EQ(g.borders(5.5), 1);  // link 0: across the upper face
    EXPECT_EQ(g.borders(3.5), 2);  // link 1: across the lower face
    EXPECT_EQ(g.borders(4.0), 0);  // exactly the width away is outside (x - lower < width)
    // A slab thinner than two widths: a particle near both faces goes both ways.
    EXPECT_EQ(slabs(4, 1, 12.0, 2.0).borders(4.5), 3);
    // The first slab's lower face is the box's, an image of the last slab's upper face.
    EXPECT_EQ(slabs(4, 0).borders(0.2), 2);
    EXPECT_EQ(slabs(4, 0).borders(12.2), 2);
    EXPECT_EQ(slabs(4, 3).borders(11.9), 1);
    // Two ranks, one link for either face.
    const SlabGeometry two = slabs(2, 1);  // owns [6, 12)
    EXPECT_EQ(two.links(), 1);
    EXPECT_EQ(two.borders(6.5), 1);
    EXPECT_EQ(two.borders(11.5), 1);
    EXPECT_EQ(two.borders(9.0), 0);
}

TEST(SlabGeometry, AlongReadsTheSlabAxis) {
    struct Position {
        double x, y, z;
    };
    SlabGeometry g = slabs(2, 0);
    for (int axis = 0; axis < 3; ++axis) {
        g.axis = axis;
        EXPECT_EQ(g.along(Position{1.0, 2.0, 3.0}), 1.0 + axis);
    }
}

struct Odd {
    const int* values;
    bool operator()(int64_t i) const { return values[i] % 2 != 0; }
};

TEST(CpuBackend, SelectKeepsTheChosenIndicesInOrder) {
    CpuBackend backend(1);
    const std::vector<int> values = {3, 4, 7, 8, 8, 1, 0, 5};
    std::vector<int64_t> out(values.size(), -1);
    const int64_t count = backend.select(static_cast<int64_t>(values.size()), Odd{values.data()}, out.data());
    ASSERT_EQ(count, 4);
    EXPECT_EQ(std::vector<int64_t>(out.begin(), out.begin() + count), (std::vector<int64_t>{0, 2, 5, 7}));
    EXPECT_EQ(backend.select(0, Odd{values.data()}, out.data()), 0);
}

}  // namespace
}  // namespace structmd
