// Blow-ups are reported, never handed back as numbers: coincident Lennard-Jones particles, a time
// step ten times too large, and a FENE bond stretched past R0 within a step. Each failure must be
// STRUCTMD_ERR_NUMERICAL with a message naming the particle id and the step; every call that returns
// STRUCTMD_OK must hand back finite values; the handle must step again once the state is repaired.
//
// The FENE bond over-stretched by structmd_set_positions and read through structmd_get_forces is
// covered by tests/python/test_c_abi.py (test_overstretched_fene_bond_is_a_numerical_error); here the
// stretch happens inside structmd_step, the path that test does not take.
#include "stability_support.hpp"

#include <cstdio>
#include <set>
#include <string>
#include <vector>

namespace structmd_stability {
namespace {

constexpr double kLiquidDensity = 0.8442;
constexpr double kLiquidTemperature = 1.44;
constexpr double kCutoff = 2.5;
constexpr double kVerletFactor = 1.12;
constexpr int kLatticeCells = 4;  // 256 particles

struct Liquid {
    SystemSpec spec;
    std::vector<Vec3> lattice;
};

// A Lennard-Jones liquid on an fcc lattice with thermal velocities: the sane state of these tests.
Liquid lennard_jones_liquid(double time_step) {
    Liquid liquid;
    double box_length = 0.0;
    liquid.lattice = fcc_lattice(kLatticeCells, kLiquidDensity, &box_length);
    liquid.spec.box = {box_length, box_length, box_length};
    liquid.spec.positions = liquid.lattice;
    liquid.spec.velocities = thermal_velocities(liquid.lattice.size(), kLiquidTemperature, 11);
    liquid.spec.force_field = lennard_jones_force_field(1.0, kCutoff, kVerletFactor, true);
    liquid.spec.integrator = velocity_verlet(time_step);
    return liquid;
}

// After a failure the handle accepts a sane state and steps: energies and forces come back finite.
void expect_steps_after_repair(structmd_sim* sim, const Liquid& liquid) {
    const std::int64_t n = particle_count(sim);
    const std::vector<double> positions = flatten(liquid.lattice);
    const std::vector<double> velocities = flatten(liquid.spec.velocities);
    ASSERT_STRUCTMD_OK(sim, structmd_set_positions(sim, positions.data(), n));
    ASSERT_STRUCTMD_OK(sim, structmd_set_velocities(sim, velocities.data(), n));
    ASSERT_STRUCTMD_OK(sim, structmd_step(sim, 20));
    EXPECT_TRUE(std::isfinite(read_energy(sim, "total")));
    EXPECT_TRUE(all_finite(read_array(sim, structmd_get_forces)));
    EXPECT_TRUE(all_finite(read_array(sim, structmd_get_positions)));
}

// Particles within the neighbour-list radius of particle `id`: a non-finite state spreads to them
// within the step that produced it, so the engine may name any of them (docs/input-format.md, Fene).
std::set<long long> neighbourhood(const std::vector<Vec3>& positions, std::size_t id, const Vec3& box) {
    std::set<long long> ids;
    const double radius = kCutoff * kVerletFactor;
    for (std::size_t j = 0; j < positions.size(); ++j) {
        double r2 = 0.0;
        for (int k = 0; k < 3; ++k) {
            const double d = minimum_image(positions[j][k] - positions[id][k], box[k]);
            r2 += d * d;
        }
        if (r2 < radius * radius) ids.insert(static_cast<long long>(j));
    }
    return ids;
}

constexpr std::size_t kFirstOfPair = 17;
constexpr std::size_t kSecondOfPair = 42;

TEST(CoincidentParticles, ForcesAreANumericalErrorNamingTheParticleAndStep) {
    Liquid liquid = lennard_jones_liquid(0.005);
    liquid.spec.positions[kSecondOfPair] = liquid.spec.positions[kFirstOfPair];
    SimHandle sim = load_document(input_document(liquid.spec));
    ASSERT_TRUE(sim);
    const std::int64_t n = particle_count(sim.get());
    constexpr double kUntouched = 12345.0;
    std::vector<double> forces(3 * n, kUntouched);
    ASSERT_EQ(structmd_get_forces(sim.get(), forces.data(), n), STRUCTMD_ERR_NUMERICAL);
    const std::string message = structmd_last_error(sim.get());
    std::printf("[ message ] %s\n", message.c_str());
    // A failed getter writes nothing into the caller's array.
    EXPECT_EQ(forces, std::vector<double>(3 * n, kUntouched));
    // Only the two coincident particles feel a non-finite force; every other pair is at r > 0.
    const long long named = number_after(message, "particle id");
    EXPECT_TRUE(named == static_cast<long long>(kFirstOfPair) || named == static_cast<long long>(kSecondOfPair))
        << message;
    EXPECT_EQ(number_after(message, "step"), 0) << message;
    ASSERT_NO_FATAL_FAILURE(expect_steps_after_repair(sim.get(), liquid));
}

TEST(CoincidentParticles, StepIsANumericalErrorNamingTheParticleAndStep) {
    const Liquid liquid = lennard_jones_liquid(0.005);
    SimHandle sim = load_document(input_document(liquid.spec));
    ASSERT_TRUE(sim);
    constexpr std::int64_t kStepsBefore = 5;
    ASSERT_STRUCTMD_OK(sim.get(), structmd_step(sim.get(), kStepsBefore));
    std::vector<double> positions = read_array(sim.get(), structmd_get_positions);
    for (int k = 0; k < 3; ++k) positions[3 * kSecondOfPair + k] = positions[3 * kFirstOfPair + k];
    const std::int64_t n = particle_count(sim.get());
    ASSERT_STRUCTMD_OK(sim.get(), structmd_set_positions(sim.get(), positions.data(), n));

    ASSERT_EQ(structmd_step(sim.get(), 10), STRUCTMD_ERR_NUMERICAL);
    const std::string message = structmd_last_error(sim.get());
    std::printf("[ message ] %s\n", message.c_str());
    // The first half kick of step 6 makes the pair's velocities non-finite; the closing check of
    // that step (the state at step 6) is the first to see it.
    EXPECT_EQ(number_after(message, "step"), kStepsBefore + 1) << message;
    std::vector<Vec3> before(n);
    for (std::int64_t i = 0; i < n; ++i) before[i] = {positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]};
    const std::set<long long> candidates = neighbourhood(before, kFirstOfPair, liquid.spec.box);
    EXPECT_EQ(candidates.count(number_after(message, "particle id")), 1u)
        << "the particle named is neither of the pair nor within the list radius of it: " << message;
    ASSERT_NO_FATAL_FAILURE(expect_steps_after_repair(sim.get(), liquid));
}

// dt = 0.05 is ten times the usual 0.005 at T = 1.44: pairs overshoot deep into the repulsive core.
// A call that returns OK must hand back finite positions, velocities, forces and energies; the
// blow-up must be reported as NUMERICAL, naming a step within the call and a particle, with the
// state back where the call started.
class OversizedTimeStep : public ::testing::TestWithParam<std::string> {};

TEST_P(OversizedTimeStep, NeverReturnsNonFiniteValuesWithOk) {
    const Liquid liquid = lennard_jones_liquid(0.05);
    SimHandle sim = load_document(input_document(liquid.spec), "cpu", GetParam());
    ASSERT_TRUE(sim);
    const std::int64_t n = particle_count(sim.get());
    constexpr std::int64_t kStepsPerCall = 10;
    constexpr std::int64_t kMaxSteps = 2000;
    std::int64_t step = 0;
    bool reported = false;
    while (step < kMaxSteps && !reported) {
        const std::vector<double> positions_before = read_array(sim.get(), structmd_get_positions);
        const std::vector<double> velocities_before = read_array(sim.get(), structmd_get_velocities);
        const structmd_status status = structmd_step(sim.get(), kStepsPerCall);
        if (status == STRUCTMD_ERR_NUMERICAL) {
            const std::string message = structmd_last_error(sim.get());
            // The getters show the last good state: the one this call started from.
            EXPECT_EQ(read_array(sim.get(), structmd_get_positions), positions_before);
            EXPECT_EQ(read_array(sim.get(), structmd_get_velocities), velocities_before);
            std::int64_t now = -1;
            ASSERT_EQ(structmd_get_step(sim.get(), &now), STRUCTMD_OK);
            EXPECT_EQ(now, step);
            std::printf("[ outcome ] %s: reported after step %lld: %s\n", GetParam().c_str(),
                        static_cast<long long>(step), message.c_str());
            const long long failed_step = number_after(message, "step");
            EXPECT_GT(failed_step, step) << message;
            EXPECT_LE(failed_step, step + kStepsPerCall) << message;
            const long long id = number_after(message, "particle id");
            EXPECT_TRUE(id >= 0 && id < n) << message;
            reported = true;
            continue;
        }
        ASSERT_EQ(status, STRUCTMD_OK) << structmd_last_error(sim.get());
        step += kStepsPerCall;
        ASSERT_TRUE(all_finite(read_array(sim.get(), structmd_get_positions))) << "step " << step;
        ASSERT_TRUE(all_finite(read_array(sim.get(), structmd_get_velocities))) << "step " << step;
        std::vector<double> forces(3 * n);
        const structmd_status force_status = structmd_get_forces(sim.get(), forces.data(), n);
        ASSERT_TRUE(force_status == STRUCTMD_OK || force_status == STRUCTMD_ERR_NUMERICAL) << force_status;
        ASSERT_TRUE(force_status != STRUCTMD_OK || all_finite(forces)) << "non-finite forces with OK, step " << step;
        double total = 0.0;
        const structmd_status energy_status = structmd_get_energy(sim.get(), "total", &total);
        ASSERT_TRUE(energy_status == STRUCTMD_OK || energy_status == STRUCTMD_ERR_NUMERICAL) << energy_status;
        ASSERT_TRUE(energy_status != STRUCTMD_OK || std::isfinite(total)) << "non-finite energy with OK, step " << step;
    }
    // Moves of about 0.1 sigma a step soon exceed the skin of 0.3 once pairs collide head-on.
    EXPECT_TRUE(reported) << "finite through " << step << " steps, total energy per particle "
                          << read_energy(sim.get(), "total") / n;
}

INSTANTIATE_TEST_SUITE_P(Precisions, OversizedTimeStep, ::testing::Values("double", "single"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

// A FENE dimer (K = 30, R0 = 1.5, r0 = 0) at r = 1 flying apart at relative speed 200: one step of
// 0.005 takes r to about 2 > R0, where the bond has no finite energy.
TEST(FeneBond, StretchedPastR0WithinAStepIsANumericalError) {
    SystemSpec spec;
    spec.box = {20.0, 20.0, 20.0};
    spec.positions = {{-0.5, 0.0, 0.0}, {0.5, 0.0, 0.0}};
    spec.velocities = {{-100.0, 0.0, 0.0}, {100.0, 0.0, 0.0}};
    spec.force_field = {{"fene",
                         {{"type", {"Bond2", "Fene"}},
                          {"labels", {"id_i", "id_j", "r0", "K", "R0"}},
                          {"data", {{0, 1, 0.0, 30.0, 1.5}}}}}};
    spec.integrator = velocity_verlet(0.005);
    SimHandle sim = load_document(input_document(spec));
    ASSERT_TRUE(sim);
    ASSERT_EQ(structmd_step(sim.get(), 3), STRUCTMD_ERR_NUMERICAL);
    const std::string message = structmd_last_error(sim.get());
    std::printf("[ message ] %s\n", message.c_str());
    EXPECT_EQ(number_after(message, "step"), 1) << message;
    const long long named = number_after(message, "particle id");
    EXPECT_TRUE(named == 0 || named == 1) << message;

    const std::vector<double> rest = flatten(spec.positions), still(6, 0.0);
    ASSERT_STRUCTMD_OK(sim.get(), structmd_set_positions(sim.get(), rest.data(), 2));
    ASSERT_STRUCTMD_OK(sim.get(), structmd_set_velocities(sim.get(), still.data(), 2));
    ASSERT_STRUCTMD_OK(sim.get(), structmd_step(sim.get(), 100));
    EXPECT_TRUE(std::isfinite(read_energy(sim.get(), "total")));
    EXPECT_TRUE(all_finite(read_array(sim.get(), structmd_get_positions)));
}

}  // namespace
// One particle given a speed of 100 with dt = 0.005 moves 0.5 in its first step, farther than the
// skin of 0.3 (cutoff 2.5, factor 1.12), though nothing is yet infinite: a fault in step 1 that
// names the displacement.
TEST(Displacement, LongerThanTheSkinInOneStepIsANumericalError) {
    SystemSpec spec;
    spec.positions = {{-2.0, 0.0, 0.0}, {2.0, 0.0, 0.0}};
    spec.velocities = {{100.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
    spec.force_field = lennard_jones_force_field(1.0, kCutoff, kVerletFactor, true);
    spec.integrator = velocity_verlet(0.005);
    SimHandle sim = load_document(input_document(spec));
    ASSERT_TRUE(sim);
    ASSERT_EQ(structmd_step(sim.get(), 5), STRUCTMD_ERR_NUMERICAL);
    const std::string message = structmd_last_error(sim.get());
    EXPECT_NE(message.find("displacement"), std::string::npos) << message;
    EXPECT_EQ(number_after(message, "step"), 1) << message;
    EXPECT_EQ(number_after(message, "particle id"), 0) << message;
    EXPECT_EQ(read_array(sim.get(), structmd_get_positions), flatten(spec.positions));
    // The host slows the particle down and the run goes on.
    const std::vector<double> slow = {1.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    ASSERT_EQ(structmd_set_velocities(sim.get(), slow.data(), 2), STRUCTMD_OK);
    EXPECT_EQ(structmd_step(sim.get(), 5), STRUCTMD_OK) << structmd_last_error(sim.get());
}

// A position a billion box lengths away cannot be wrapped into an image count: rejected, with the
// state unchanged and the handle usable.
TEST(FarPositions, BeyondWhatImagesCountAreRejected) {
    SystemSpec spec;
    spec.positions = {{-2.0, 0.0, 0.0}, {2.0, 0.0, 0.0}};
    spec.force_field = lennard_jones_force_field(1.0, kCutoff, kVerletFactor, true);
    spec.integrator = velocity_verlet(0.005);
    SimHandle sim = load_document(input_document(spec));
    ASSERT_TRUE(sim);
    const std::vector<double> far = {3e10, 0.0, 0.0, 2.0, 0.0, 0.0};
    ASSERT_EQ(structmd_set_positions(sim.get(), far.data(), 2), STRUCTMD_ERR_ARGUMENT);
    const std::string message = structmd_last_error(sim.get());
    EXPECT_NE(message.find("particle id 0"), std::string::npos) << message;
    EXPECT_EQ(read_array(sim.get(), structmd_get_positions), flatten(spec.positions));
    EXPECT_EQ(structmd_step(sim.get(), 10), STRUCTMD_OK) << structmd_last_error(sim.get());
}

}  // namespace structmd_stability
