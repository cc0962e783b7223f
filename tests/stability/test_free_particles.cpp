// Particles that feel nothing: a lone particle (with and without a pair potential, whose list then
// holds no pair), and many particles with no force field at all. Velocity Verlet must move them at
// constant velocity, x(t) = x0 + v t wrapped into the box, with zero force and zero potential energy,
// and the engine should not do work that such a scene does not need.
#include "stability_support.hpp"

#include <cstdio>
#include <string>
#include <vector>

namespace structmd_stability {
namespace {

// x wrapped into [-L/2, L/2).
double wrapped(double x, double box_length) { return x - box_length * std::floor(x / box_length + 0.5); }

struct LoneParticleCase {
    std::string name;
    bool with_pair_potential;
};

class LoneParticle : public ::testing::TestWithParam<LoneParticleCase> {};

// 2000 steps of 0.005 move the particle by 7, -13 and 14.5: across the box (L = 8) on every axis.
// Each step adds dt v to a coordinate below 4 in size, rounding by at most 2^-51 (half an ulp of 4),
// so after 2000 steps the position is within 2000 x 2^-51 ~ 1e-12 of x0 + v t; a missed or extra
// wrap is off by 8.
TEST_P(LoneParticle, MovesAtConstantVelocityWithZeroForceAndEnergy) {
    constexpr double kTimeStep = 0.005, kBoxLength = 8.0;
    constexpr std::int64_t kStepsPerCall = 500, kCalls = 4;
    const Vec3 x0{0.3, -1.7, 2.9}, v{0.7, -1.3, 1.45};
    SystemSpec spec;
    spec.box = {kBoxLength, kBoxLength, kBoxLength};
    spec.positions = {x0};
    spec.velocities = {v};
    spec.integrator = velocity_verlet(kTimeStep);
    if (GetParam().with_pair_potential) spec.force_field = lennard_jones_force_field(1.0, 2.5, 1.12, false);
    SimHandle sim = load_document(input_document(spec));
    ASSERT_TRUE(sim);
    const double kinetic = 0.5 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (std::int64_t call = 1; call <= kCalls; ++call) {
        ASSERT_STRUCTMD_OK(sim.get(), structmd_step(sim.get(), kStepsPerCall));
        const double t = call * kStepsPerCall * kTimeStep;
        const std::vector<double> x = read_array(sim.get(), structmd_get_positions);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(x[k], wrapped(x0[k] + v[k] * t, kBoxLength), 1e-12) << "axis " << k;
        EXPECT_EQ(read_array(sim.get(), structmd_get_velocities), std::vector<double>(v.begin(), v.end()));
        EXPECT_EQ(read_array(sim.get(), structmd_get_forces), std::vector<double>(3, 0.0));
        EXPECT_EQ(read_energy(sim.get(), "potential"), 0.0);
        EXPECT_DOUBLE_EQ(read_energy(sim.get(), "kinetic"), kinetic);
        EXPECT_DOUBLE_EQ(read_energy(sim.get(), "total"), kinetic);
    }
}

INSTANTIATE_TEST_SUITE_P(ForceFields, LoneParticle,
                         ::testing::Values(LoneParticleCase{"NoForceField", false},
                                           LoneParticleCase{"LennardJones", true}),
                         [](const ::testing::TestParamInfo<LoneParticleCase>& info) { return info.param.name; });

// 64 particles and no force field. Positions are multiples of 2^-6, velocities multiples of 2^-4 in
// [-2, 2], the time step 2^-7 and the box 8: every x0 + n dt v is a multiple of 2^-11 below 2^10 in
// size, so velocity Verlet (adding dt v each step, the half kicks adding exactly zero) and wrapping
// (subtracting multiples of 8) are exact, and the positions must equal x0 + v t mod L bit for bit.
TEST(NoInteractions, FreeFlightIsExactAndTheEnergyIsKineticOnly) {
    constexpr double kTimeStep = 1.0 / 128.0, kBoxLength = 8.0;
    constexpr std::int64_t kStepsPerCall = 250, kCalls = 4;
    constexpr int kParticles = 64;
    SplitMix64 rng(81);
    SystemSpec spec;
    spec.box = {kBoxLength, kBoxLength, kBoxLength};
    spec.integrator = velocity_verlet(kTimeStep);
    double kinetic = 0.0;
    for (int i = 0; i < kParticles; ++i) {
        Vec3 x, v;
        for (int k = 0; k < 3; ++k) {
            x[k] = std::floor(rng.uniform(-4.0, 4.0) * 64.0) / 64.0;
            v[k] = std::floor(rng.uniform(-2.0, 2.0) * 16.0) / 16.0;
            kinetic += 0.5 * v[k] * v[k];
        }
        spec.positions.push_back(x);
        spec.velocities.push_back(v);
    }
    SimHandle sim = load_document(input_document(spec));
    ASSERT_TRUE(sim);
    for (std::int64_t call = 1; call <= kCalls; ++call) {
        ASSERT_STRUCTMD_OK(sim.get(), structmd_step(sim.get(), kStepsPerCall));
        const double t = call * kStepsPerCall * kTimeStep;
        double time = 0.0;
        ASSERT_STRUCTMD_OK(sim.get(), structmd_get_time(sim.get(), &time));
        EXPECT_EQ(time, t);
        const std::vector<double> x = read_array(sim.get(), structmd_get_positions);
        for (int i = 0; i < kParticles; ++i)
            for (int k = 0; k < 3; ++k)
                ASSERT_EQ(x[3 * i + k], wrapped(spec.positions[i][k] + spec.velocities[i][k] * t, kBoxLength))
                    << "particle " << i << ", axis " << k << ", t = " << t;
        EXPECT_EQ(read_array(sim.get(), structmd_get_velocities), flatten(spec.velocities));
    }
    EXPECT_EQ(read_energy(sim.get(), "potential"), 0.0);
    EXPECT_EQ(read_energy(sim.get(), "kinetic"), kinetic);
    EXPECT_EQ(read_energy(sim.get(), "total"), kinetic);
    EXPECT_EQ(read_array(sim.get(), structmd_get_particle_energies, 1), std::vector<double>(kParticles, 0.0));

    // No pair term: no list. Energies were asked for once per state (the three terms above share one
    // evaluation) and the virial never. Forces are needed at most once per step: a zero force
    // field evaluated more often than that is work for nothing.
    const json counters = read_counters(sim.get());
    std::printf("[ counters ] %s\n", counters.dump().c_str());
    EXPECT_EQ(counters["neighbour_list_builds"], 0);
    EXPECT_LE(counters["energy_evaluations"].get<std::int64_t>(), 1);
    EXPECT_EQ(counters["virial_evaluations"], 0);
    EXPECT_LE(counters["force_evaluations"].get<std::int64_t>(), kCalls * kStepsPerCall + 1);

    // Without forces the virial is zero and the pressure is the ideal gas's, 2K / (3V).
    EXPECT_EQ(read_virial(sim.get()), std::vector<double>(9, 0.0));
    double pressure = NAN;
    ASSERT_STRUCTMD_OK(sim.get(), structmd_get_pressure(sim.get(), &pressure));
    EXPECT_DOUBLE_EQ(pressure, 2.0 * kinetic / (3.0 * std::pow(kBoxLength, 3)));
}

}  // namespace
}  // namespace structmd_stability
