// Cluster pairs (neighbour/cluster_view.hpp) against an all-pairs search and against the
// per-particle pair kernel: every pair within the cutoff must be met exactly once from each side
// after builds, after moves under half the skin and when a cluster's list overflows; the cluster
// kernel must give the forces, energies and virials of PairKernel over the per-particle lists.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <vector>

#include "backends/cpu/cpu_backend.hpp"
#include "forcefield/cluster_pair_kernel.hpp"
#include "forcefield/lennard_jones.hpp"
#include "neighbour/verlet_list.hpp"
#include "random_particles.hpp"

namespace structmd {
namespace {

using List = VerletList<CpuBackend, double>;

struct System : RandomParticles {
    using RandomParticles::RandomParticles;

    // The pairs the cluster kernel would meet within the cutoff, each once from each side.
    Pairs met(List& list, double cutoff) {
        list.update(pos, n, box, ++version);
        EXPECT_TRUE(list.clusters());
        const ClusterView<double> v = list.cluster_view();
        Pairs seen;
        std::vector<int> slots(n, 0);
        for (int c = 0; c < v.clusters; ++c)
            for (int s = v.bounds[2 * c]; s < v.bounds[2 * c + 1]; ++s) {
                ++slots[v.order[s]];
                v.for_each_partner(c, 0, 1, [&](int first, int end) {
                    for (int t = first; t < end; ++t) {
                        const Vec3<double> d = box.minimum_image(xyz(v.positions[t]) - xyz(v.positions[s]));
                        if (t == s || !(dot(d, d) < cutoff * cutoff)) continue;
                        EXPECT_TRUE(seen.insert({v.order[s], v.order[t]}).second)
                            << "pair (" << v.order[s] << ", " << v.order[t] << ") met twice";
                    }
                });
            }
        for (int64_t i = 0; i < n; ++i) EXPECT_EQ(slots[i], 1) << "particle " << i << " is in " << slots[i] << " clusters";
        return seen;
    }
};

List clustered(System& s, double cutoff, double factor) {
    return List(s.backend, cutoff, factor, PairCondition::all, {}, nullptr, 1, nullptr, true);
}

TEST(ClusterPairs, MeetEveryPairAfterABuildAndMovesBelowHalfTheSkin) {
    System s(900, 12.0, 13.0, 14.0, 1);
    List list = clustered(s, 2.5, 1.12);  // skin 0.3
    EXPECT_EQ(s.met(list, 2.5), s.pairs_within(2.5));
    for (int k = 0; k < 5; ++k) {
        s.jiggle(0.029, 10 + k);  // at most 0.145 < 0.15 in all: no rebuild
        EXPECT_EQ(s.met(list, 2.5), s.pairs_within(2.5));
    }
    list.adapt();
    EXPECT_EQ(list.builds(), 1);
    s.jiggle(0.16, 20);
    EXPECT_EQ(s.met(list, 2.5), s.pairs_within(2.5));
    list.adapt();
    EXPECT_EQ(list.builds(), 2);
}

TEST(ClusterPairs, OverflowingListsScanTheAdjacentCellsThenGrow) {
    // Half the particles in a dense blob: the blob's clusters have more partners than the first
    // capacity guess, and crowded cells keep particle order (no sub-cell sort).
    System s(600, 20.0, 20.0, 20.0, 5);
    for (int64_t i = 0; i < s.n; i += 2) {
        Real4<double>& p = s.pos.data()[i];
        p = {0.15 * p.x, 0.15 * p.y, 0.15 * p.z, 0.0};
    }
    List list = clustered(s, 2.5, 1.1);
    EXPECT_EQ(s.met(list, 2.5), s.pairs_within(2.5));
    const ClusterView<double> before = list.cluster_view();
    int overflowing = 0;
    for (int c = 0; c < before.clusters; ++c) overflowing += before.count[c] > before.capacity;
    EXPECT_GT(overflowing, 0) << "the blob was meant to overflow the first capacity";
    list.adapt();
    list.invalidate();
    EXPECT_EQ(s.met(list, 2.5), s.pairs_within(2.5));
    const ClusterView<double> after = list.cluster_view();
    for (int c = 0; c < after.clusters; ++c) EXPECT_LE(after.count[c], after.capacity);
}

TEST(ClusterPairs, PerParticleListsAreExactBeforeAndAfterTheyAreBuilt) {
    System s(700, 12.0, 12.0, 12.0, 3);
    List list = clustered(s, 2.5, 1.12);
    s.met(list, 2.5);
    const auto visited = [&](const NeighbourView<double>& view) {
        Pairs seen;
        for (int k = 0; k < s.n; ++k)
            view.for_each_neighbour(k, [&](int t) {
                const Vec3<double> d = s.box.minimum_image(xyz(view.positions[t]) - xyz(view.positions[k]));
                if (dot(d, d) < 2.5 * 2.5) seen.insert({view.order[k], view.order[t]});
            });
        return seen;
    };
    // Not built yet: the view scans the cells.
    const NeighbourView<double> scanning = list.view();
    EXPECT_LT(scanning.capacity, 0);
    EXPECT_EQ(visited(scanning), s.pairs_within(2.5));
    // Asked for once, they are built at the next update, beside the clusters.
    s.met(list, 2.5);
    const NeighbourView<double> listed = list.view();
    EXPECT_GT(listed.capacity, 0);
    for (int k = 0; k < s.n; ++k) EXPECT_LE(listed.count[k], listed.capacity);
    EXPECT_EQ(visited(listed), s.pairs_within(2.5));
}

TEST(ClusterPairs, OnlyForListsTheClusterKernelsHandle) {
    System s(300, 12.0, 12.0, 12.0, 4);
    PairFilterInputs exclusions;
    exclusions.excluded.assign(s.n, {});
    exclusions.excluded[0] = {1};
    exclusions.excluded[1] = {0};
    List excluding(s.backend, 2.5, 1.1, PairCondition::all, exclusions, nullptr, 1, nullptr, true);
    excluding.update(s.pos, s.n, s.box, 1);
    EXPECT_FALSE(excluding.clusters());
    System narrow(200, 12.0, 12.0, 8.0, 5);  // 2 cells along z: a centre's image is not its particles'
    List small = clustered(narrow, 2.5, 1.1);
    small.update(narrow.pos, narrow.n, narrow.box, 1);
    EXPECT_FALSE(small.clusters());
}

// Forces, energies and virials of an LJ liquid of two types, over clusters and over per-particle
// lists, with and without a group.
TEST(ClusterPairs, KernelAgreesWithThePerParticleKernel) {
    System s(1500, 13.0, 14.0, 15.0, 6);
    // A liquid rather than random points, so no pair sits at r ~ 0: a jittered cubic lattice.
    const int side = 12;
    for (int64_t i = 0; i < s.n; ++i) {
        Real4<double>& p = s.pos.data()[i];
        const int64_t a = i % side, b = (i / side) % side, c = i / (side * side);
        p = {(a + 0.3 * p.x / 13.0) * 13.0 / side - 6.5, (b + 0.3 * p.y / 14.0) * 14.0 / side - 7.0,
             (c + 0.3 * p.z / 15.0) * 15.0 / 11 - 7.5, static_cast<double>(i % 2)};
        const Vec3<double> r = s.box.wrap(xyz(p));
        p = {r.x, r.y, r.z, p.w};
    }
    using LJ = LennardJonesType1;
    using Params = LJ::Params<double>;
    std::vector<Params> table;
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) table.push_back(LJ::make_pair_params<double>(1.0 + 0.2 * (a + b), 1.0 + 0.05 * (a + b), 2.5, true));
    HostBuffer<Params> params;
    s.backend.upload(params, table.data(), table.size());
    HostBuffer<uint8_t> group;
    s.backend.resize(group, s.n);
    for (int64_t i = 0; i < s.n; ++i) group.data()[i] = i % 3 != 0;

    struct Result {
        std::vector<Real4<double>> force;
        std::vector<double> energy;
        std::vector<Tensor3<double>> virial;
    };
    const auto run = [&](bool clusters, const uint8_t* members) {
        List list(s.backend, 2.5, 1.12, PairCondition::all, {}, nullptr, 1, nullptr, clusters);
        list.update(s.pos, s.n, s.box, 1);
        EXPECT_EQ(list.clusters(), clusters);
        Result r{std::vector<Real4<double>>(s.n, Real4<double>{0, 0, 0, 0}), std::vector<double>(s.n, 0.0),
                 std::vector<Tensor3<double>>(s.n, zero_tensor<double>())};
        ForceOutputs<double> out;
        out.force = r.force.data();
        out.energy = r.energy.data();
        out.virial = r.virial.data();
        const PairTable<Params> pairs{params.data(), 2, nullptr};
        if (clusters)
            s.backend.for_each_lanes(list.cluster_view().clusters,
                                     ClusterPairKernel<LJ, double, double, true, true, true>{
                                         nullptr, nullptr, members, list.cluster_view(), pairs, out},
                                     LaneSizing::kWarp);
        else
            s.backend.for_each_lanes(s.n, PairKernel<LJ, double, double, true, true, true>{nullptr, nullptr, members,
                                                                                          list.view(), pairs, out});
        return r;
    };
    for (const uint8_t* members : {static_cast<const uint8_t*>(nullptr), static_cast<const uint8_t*>(group.data())}) {
        const Result reference = run(false, members), clustered = run(true, members);
        double largestForce = 0.0;
        for (int64_t i = 0; i < s.n; ++i) largestForce = std::max(largestForce, std::abs(reference.force[i].x));
        ASSERT_GT(largestForce, 1.0) << "the liquid was meant to have forces";
        for (int64_t i = 0; i < s.n; ++i) {
            const double tolerance = 1e-12 * (1.0 + largestForce);
            EXPECT_NEAR(clustered.force[i].x, reference.force[i].x, tolerance) << "particle " << i;
            EXPECT_NEAR(clustered.force[i].y, reference.force[i].y, tolerance) << "particle " << i;
            EXPECT_NEAR(clustered.force[i].z, reference.force[i].z, tolerance) << "particle " << i;
            EXPECT_NEAR(clustered.energy[i], reference.energy[i], 1e-12) << "particle " << i;
            EXPECT_NEAR(clustered.virial[i].xy, reference.virial[i].xy, 1e-11) << "particle " << i;
            EXPECT_NEAR(clustered.virial[i].zz, reference.virial[i].zz, 1e-11) << "particle " << i;
            if (members && !members[i]) EXPECT_EQ(clustered.force[i].x, 0.0) << "particle " << i << " is not in the group";
        }
    }
}

}  // namespace
}  // namespace structmd
