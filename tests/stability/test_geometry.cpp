// Odd geometries against an all-pairs Lennard-Jones reference in double precision: particles given
// a thousand box lengths outside the box, every particle within one cell, and boxes barely longer
// than twice the cutoff (and shorter ones, which must be rejected).
//
// Tolerances: the engine and the reference sum the same pair terms in double precision, in different
// orders, so forces agree to ~1e-15 relative to the largest force (measured); 1e-10 leaves room for
// that and for the position rounding of wrapping (below), while a missing pair, a pair counted twice
// or a wrong image changes the forces or the energy by 1e-6 relative or more: each pair adds a force
// of at least ~3e-3 or an energy of magnitude near 1 (near the LJ minimum, where its force vanishes),
// against largest forces of at most ~1e3 and potential energies of at most a few hundred.
#include "stability_support.hpp"

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

namespace structmd_stability {
namespace {

using structmd_physics::max_relative_deviation;
using structmd_physics::relative_deviation;

constexpr double kCutoff = 2.5;
constexpr double kForceTolerance = 1e-10;
constexpr double kEnergyTolerance = 1e-10;

SystemSpec lennard_jones_system(const Vec3& box, const std::vector<Vec3>& positions, double sigma,
                                double cutoff_factor) {
    SystemSpec spec;
    spec.box = box;
    spec.positions = positions;
    spec.velocities.assign(positions.size(), Vec3{0.0, 0.0, 0.0});
    spec.force_field = lennard_jones_force_field(sigma, cutoff_factor, 1.12, true);
    spec.integrator = velocity_verlet(0.001);
    return spec;
}

// The engine's forces, potential energy and virial against the all-pairs reference of its own
// positions (read back, so that the comparison holds whatever the engine wrapped).
void expect_matches_all_pairs(structmd_sim* sim, const Vec3& box, double sigma, double cutoff) {
    const std::vector<double> xyz = read_array(sim, structmd_get_positions);
    const PairReference reference = all_pairs_lennard_jones(xyz, box, sigma, cutoff, true);
    ASSERT_GT(reference.pairs_within_cutoff, 0) << "the configuration tests nothing";
    const std::vector<double> forces = read_array(sim, structmd_get_forces);
    const double force_deviation = max_relative_deviation(forces, reference.forces);
    const double energy = read_energy(sim, "potential");
    const double virial_deviation = max_relative_deviation(read_virial(sim), reference.virial);
    std::printf("[ deviation ] %d pairs: forces %.2e, energy %.2e, virial %.2e\n", reference.pairs_within_cutoff,
                force_deviation, relative_deviation(energy, reference.energy), virial_deviation);
    EXPECT_LT(force_deviation, kForceTolerance);
    EXPECT_LT(relative_deviation(energy, reference.energy), kEnergyTolerance);
    EXPECT_LT(virial_deviation, kForceTolerance);
}

// ---- far outside the box ------------------------------------------------------------------------

constexpr double kFarBoxLength = 8.0;
constexpr int kFarParticles = 60;

// Each coordinate shifted by a whole number of box lengths between 1000 and 1003, of either sign.
std::vector<Vec3> shifted_far_away(const std::vector<Vec3>& positions, std::uint64_t seed) {
    SplitMix64 rng(seed);
    std::vector<Vec3> far = positions;
    for (Vec3& r : far)
        for (double& x : r) {
            const double images = std::floor(rng.uniform(1000.0, 1004.0));
            x += (rng.uniform(0.0, 1.0) < 0.5 ? -images : images) * kFarBoxLength;
        }
    return far;
}

// Wrapping x + 1003 L to x costs the rounding of a number near 8000: |error| <= 1003 L 2^-53 ~ 1e-12,
// which moves a force by ~1e-11 relative (|d ln F / dr| ~ 13 / r at r ~ 1), inside kForceTolerance.
constexpr double kWrapTolerance = 1e-11;

// The unwrapped positions a WriteStep with pbc false writes at the first step: the file holds
// %.8g numbers, so each matches the input to 5e-8 relative; a wrong image is off by 8.
std::vector<double> unwrapped_frame(structmd_sim* sim, const std::string& path) {
    EXPECT_EQ(structmd_step(sim, 1), STRUCTMD_OK) << structmd_last_error(sim);
    std::ifstream file(path);
    std::size_t count = 0;
    std::string comment, type;
    file >> count;
    std::getline(file, comment);
    std::getline(file, comment);
    std::vector<double> xyz(3 * count);
    std::string rest;  // the atomic number and type columns
    for (std::size_t i = 0; i < count; ++i) {
        file >> type >> xyz[3 * i] >> xyz[3 * i + 1] >> xyz[3 * i + 2];
        std::getline(file, rest);
    }
    EXPECT_TRUE(file) << "could not read " << count << " positions from " << path;
    return xyz;
}

json unwrapped_writer(const std::string& path_without_extension) {
    return {{"unwrapped",
             {{"type", {"WriteStep", "WriteStep"}},
              {"parameters",
               {{"intervalStep", 1}, {"outputFilePath", path_without_extension}, {"outputFormat", "xyz"}, {"pbc", false}}}}}};
}

void expect_same_numbers(const std::vector<double>& actual, const std::vector<double>& expected, double relative,
                         const std::string& what) {
    ASSERT_EQ(actual.size(), expected.size()) << what;
    for (std::size_t k = 0; k < actual.size(); ++k)
        ASSERT_NEAR(actual[k], expected[k], relative * std::abs(expected[k]) + kWrapTolerance)
            << what << ", particle " << k / 3 << ", axis " << k % 3;
}

TEST(FarOutsideTheBox, WrappedOnLoadWithTheSameForcesAndUnwrappedPositions) {
    const Vec3 box{kFarBoxLength, kFarBoxLength, kFarBoxLength};
    const std::vector<Vec3> inside = random_positions(box, kFarParticles, 0.9, 31);
    const std::vector<Vec3> far = shifted_far_away(inside, 32);
    SimHandle near_sim = load_document(input_document(lennard_jones_system(box, inside, 1.0, kCutoff)));
    const std::string path = ::testing::TempDir() + "structmd_far_on_load";
    SystemSpec far_spec = lennard_jones_system(box, far, 1.0, kCutoff);
    far_spec.simulation_step = unwrapped_writer(path);
    SimHandle far_sim = load_document(input_document(far_spec));
    ASSERT_TRUE(near_sim && far_sim);

    expect_same_numbers(read_array(far_sim.get(), structmd_get_positions), flatten(inside), 0.0, "wrapped position");
    const std::vector<double> reference_forces = read_array(near_sim.get(), structmd_get_forces);
    EXPECT_LT(max_relative_deviation(read_array(far_sim.get(), structmd_get_forces), reference_forces), kForceTolerance);
    EXPECT_LT(relative_deviation(read_energy(far_sim.get(), "potential"), read_energy(near_sim.get(), "potential")),
              kEnergyTolerance);
    EXPECT_LT(max_relative_deviation(read_array(far_sim.get(), structmd_get_particle_energies, 1),
                                     read_array(near_sim.get(), structmd_get_particle_energies, 1)),
              kEnergyTolerance);
    expect_same_numbers(unwrapped_frame(far_sim.get(), path + ".xyz"), flatten(far), 5e-8, "unwrapped position");
}

TEST(FarOutsideTheBox, WrappedBySetPositionsWithTheSameForcesAndUnwrappedPositions) {
    const Vec3 box{kFarBoxLength, kFarBoxLength, kFarBoxLength};
    const std::vector<Vec3> inside = random_positions(box, kFarParticles, 0.9, 41);
    const std::vector<Vec3> far = shifted_far_away(inside, 42);
    const std::string path = ::testing::TempDir() + "structmd_far_set";
    SystemSpec spec = lennard_jones_system(box, inside, 1.0, kCutoff);
    spec.simulation_step = unwrapped_writer(path);
    SimHandle sim = load_document(input_document(spec));
    ASSERT_TRUE(sim);
    const std::vector<double> reference_forces = read_array(sim.get(), structmd_get_forces);
    const double reference_energy = read_energy(sim.get(), "potential");

    const std::vector<double> far_xyz = flatten(far);
    ASSERT_STRUCTMD_OK(sim.get(), structmd_set_positions(sim.get(), far_xyz.data(), kFarParticles));
    expect_same_numbers(read_array(sim.get(), structmd_get_positions), flatten(inside), 0.0, "wrapped position");
    EXPECT_LT(max_relative_deviation(read_array(sim.get(), structmd_get_forces), reference_forces), kForceTolerance);
    EXPECT_LT(relative_deviation(read_energy(sim.get(), "potential"), reference_energy), kEnergyTolerance);
    expect_same_numbers(unwrapped_frame(sim.get(), path + ".xyz"), far_xyz, 5e-8, "unwrapped position");
}

// ---- every particle in one cell -----------------------------------------------------------------

// 64 particles on a 4^3 cubic lattice of spacing 0.12 jittered by up to 0.01 per axis: the cluster
// spans under 0.4, far less than the cutoff 2.5 and the cells (>= 2.8), so every pair interacts.
// Lennard-Jones with sigma 0.1 (cutOffFactor 25): no pair is closer than 0.1 = sigma, so forces stay
// finite (|F| <~ 1e3) while the list and the cells hold 64 particles where ~1 is expected.
std::vector<Vec3> tight_cluster(const Vec3& centre, std::uint64_t seed) {
    SplitMix64 rng(seed);
    std::vector<Vec3> positions;
    for (int ix = 0; ix < 4; ++ix)
        for (int iy = 0; iy < 4; ++iy)
            for (int iz = 0; iz < 4; ++iz) {
                const int index[3] = {ix, iy, iz};
                Vec3 r;
                for (int k = 0; k < 3; ++k) r[k] = centre[k] + 0.12 * (index[k] - 1.5) + rng.uniform(-0.01, 0.01);
                positions.push_back(r);
            }
    return positions;
}

struct ClusterCase {
    std::string name;
    Vec3 centre;
};

class ClusterInOneCell : public ::testing::TestWithParam<ClusterCase> {};

TEST_P(ClusterInOneCell, ForcesEqualAllPairsBeforeAndAfterSteps) {
    constexpr double kSigma = 0.1, kCutoffFactor = 25.0;
    const Vec3 box{20.0, 20.0, 20.0};
    const SystemSpec spec = lennard_jones_system(box, tight_cluster(GetParam().centre, 51), kSigma, kCutoffFactor);
    SimHandle sim = load_document(input_document(spec));
    ASSERT_TRUE(sim);
    ASSERT_NO_FATAL_FAILURE(expect_matches_all_pairs(sim.get(), box, kSigma, kSigma * kCutoffFactor));
    // Steps run the list again with the capacities enlarged after the first overflow.
    ASSERT_STRUCTMD_OK(sim.get(), structmd_step(sim.get(), 20));
    ASSERT_NO_FATAL_FAILURE(expect_matches_all_pairs(sim.get(), box, kSigma, kSigma * kCutoffFactor));
}

INSTANTIATE_TEST_SUITE_P(Clusters, ClusterInOneCell,
                         ::testing::Values(ClusterCase{"AtTheCentre", {0.0, 0.0, 0.0}},
                                           ClusterCase{"AcrossTheCorner", {10.0, -10.0, 10.0}}),
                         [](const ::testing::TestParamInfo<ClusterCase>& info) { return info.param.name; });

// ---- boxes near twice the cutoff ----------------------------------------------------------------

constexpr double kBarelyTwoCutoffs = 2.0 * kCutoff + 1e-6;

struct BoxCase {
    std::string name;
    Vec3 box;
};

class BoxBarelyTwiceTheCutoff : public ::testing::TestWithParam<BoxCase> {};

// Density about 0.7, no pair closer than 0.9: the list radius (2.8) exceeds half the box, so one
// cell spans the short axes and the minimum image alone must keep each pair once.
TEST_P(BoxBarelyTwiceTheCutoff, ForcesEnergyAndVirialEqualAllPairs) {
    const Vec3& box = GetParam().box;
    const auto n = static_cast<std::size_t>(0.7 * box[0] * box[1] * box[2]);
    SimHandle sim = load_document(input_document(lennard_jones_system(box, random_positions(box, n, 0.9, 61), 1.0, kCutoff)));
    ASSERT_TRUE(sim);
    ASSERT_NO_FATAL_FAILURE(expect_matches_all_pairs(sim.get(), box, 1.0, kCutoff));
    ASSERT_STRUCTMD_OK(sim.get(), structmd_step(sim.get(), 50));
    ASSERT_NO_FATAL_FAILURE(expect_matches_all_pairs(sim.get(), box, 1.0, kCutoff));
}

INSTANTIATE_TEST_SUITE_P(
    Boxes, BoxBarelyTwiceTheCutoff,
    ::testing::Values(BoxCase{"EveryAxis", {kBarelyTwoCutoffs, kBarelyTwoCutoffs, kBarelyTwoCutoffs}},
                      BoxCase{"OneAxis", {9.0, kBarelyTwoCutoffs, 7.5}}),
    [](const ::testing::TestParamInfo<BoxCase>& info) { return info.param.name; });

class BoxNotTwiceTheCutoff : public ::testing::TestWithParam<BoxCase> {};

// The documented rule is cutoff < L/2: a box of exactly 2 r_c is rejected too.
TEST_P(BoxNotTwiceTheCutoff, IsRejectedOnLoadNamingTheCutoff) {
    const Vec3& box = GetParam().box;
    const SystemSpec spec = lennard_jones_system(box, {{0.0, 0.0, 0.0}, {1.2, 0.0, 0.0}}, 1.0, kCutoff);
    structmd_sim* raw = nullptr;
    ASSERT_EQ(structmd_create(create_options("cpu", "double").c_str(), &raw), STRUCTMD_OK);
    SimHandle sim(raw);
    ASSERT_EQ(structmd_load_string(sim.get(), input_document(spec).dump().c_str()), STRUCTMD_ERR_INPUT);
    const std::string message = structmd_last_error(sim.get());
    std::printf("[ message ] %s\n", message.c_str());
    EXPECT_NE(message.find("topology.forceField.lj.parameters.cutOffFactor"), std::string::npos) << message;
    EXPECT_NE(message.find("half the box"), std::string::npos) << message;
}

TEST_P(BoxNotTwiceTheCutoff, IsRejectedBySetBoxKeepingTheState) {
    const Vec3 box{8.0, 8.0, 8.0};
    SimHandle sim = load_document(input_document(lennard_jones_system(box, random_positions(box, 40, 0.9, 71), 1.0, kCutoff)));
    ASSERT_TRUE(sim);
    const std::vector<double> positions = read_array(sim.get(), structmd_get_positions);
    const double lengths[3] = {GetParam().box[0], GetParam().box[1], GetParam().box[2]};
    ASSERT_EQ(structmd_set_box(sim.get(), lengths), STRUCTMD_ERR_ARGUMENT);
    const std::string message = structmd_last_error(sim.get());
    std::printf("[ message ] %s\n", message.c_str());
    EXPECT_NE(message.find("cutoff"), std::string::npos) << message;
    EXPECT_NE(message.find("half the box"), std::string::npos) << message;
    double kept[3];
    ASSERT_STRUCTMD_OK(sim.get(), structmd_get_box(sim.get(), kept));
    EXPECT_EQ(std::vector<double>(kept, kept + 3), std::vector<double>(box.begin(), box.end()));
    EXPECT_EQ(read_array(sim.get(), structmd_get_positions), positions);
}

constexpr double kBarelyUnderTwoCutoffs = 2.0 * kCutoff - 1e-6;

INSTANTIATE_TEST_SUITE_P(
    Boxes, BoxNotTwiceTheCutoff,
    ::testing::Values(BoxCase{"EveryAxisShort", {kBarelyUnderTwoCutoffs, kBarelyUnderTwoCutoffs, kBarelyUnderTwoCutoffs}},
                      BoxCase{"OneAxisShort", {9.0, 9.0, kBarelyUnderTwoCutoffs}},
                      BoxCase{"OneAxisExactlyTwice", {2.0 * kCutoff, 9.0, 9.0}}),
    [](const ::testing::TestParamInfo<BoxCase>& info) { return info.param.name; });

}  // namespace
}  // namespace structmd_stability
