// A million steps of velocity Verlet on a small Lennard-Jones system (CPU, double precision, one
// thread): the total energy per particle must not drift.
//
// System: 108 particles (fcc, 3^3 cells) at density 0.8442, Lennard-Jones cut at 2.5 sigma and
// shifted so the energy is continuous, velocities at T = 1.44 that equipartition to T ~ 0.70,
// dt = 0.005: 1e6 steps are 5000 tau. The total energy per particle e(t) is sampled every 1000 steps
// and the drift is the least-squares slope of e against t.
//
// The bound comes from shorter runs of this very system (seeds 1 to 8 of the velocities, 125000
// steps = 625 tau each, measured with the engine on this machine): fitted slopes of
// +2.1e-7, +1.7e-6, +1.1e-6, +5.7e-7, -1.4e-6, -5.0e-7, +9.4e-7, +2.3e-6 per tau, mean 6.2e-7 and
// standard deviation 1.2e-6, with no consistent sign. The energy wanders like a random walk, as it
// should: the shifted potential still has a force step of 0.039 at the cutoff, and each pair
// crossing it adds an error of random sign. For a random walk of variance rate s^2, the fitted slope
// over a time T has variance 6 s^2 / (5 T); the short runs give s^2 = 7.5e-10 per tau, so one fit
// over 5000 tau scatters by 4.2e-7 per tau. The bound, 2.5e-6 per tau (1.25e-2 per particle over the
// run), is the short runs' mean slope plus 4.5 of those standard deviations. The million-step run
// itself measured -1.2e-7 per tau (-5.9e-4 over the run). A velocity Verlet step missing its second
// half kick drifts by 4e-3 per tau on a similar liquid (0.04 over 10 tau,
// tests/physics/test_nve_conservation.cpp), three orders of magnitude over the bound.
//
// Runtime on one core here: 90 to 120 s (2 cores shared with other builds, load 3 to 5). The test
// is labelled long (ctest -LE long leaves it out of a quick local run); CI runs it.
#include "stability_support.hpp"

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace structmd_stability {
namespace {

constexpr int kLatticeCells = 3;  // 108 particles
constexpr double kDensity = 0.8442;
constexpr double kInitialTemperature = 1.44;
constexpr double kTimeStep = 0.005;
constexpr std::int64_t kSteps = 1000000;
constexpr std::int64_t kStepsPerSample = 1000;
constexpr double kMaxDriftRate = 2.5e-6;  // |slope| of total energy per particle, per tau
// The lattice melts: its potential energy per particle rises from -6.33 to a mean of -5.23; a run
// that did not move the particles would keep it.
constexpr double kMinPotentialRise = 0.5;

double fitted_slope(const std::vector<double>& t, const std::vector<double>& e) {
    double mean_t = 0.0, mean_e = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) {
        mean_t += t[i] / t.size();
        mean_e += e[i] / e.size();
    }
    double covariance = 0.0, variance = 0.0;
    for (std::size_t i = 0; i < t.size(); ++i) {
        covariance += (t[i] - mean_t) * (e[i] - mean_e);
        variance += (t[i] - mean_t) * (t[i] - mean_t);
    }
    return covariance / variance;
}

TEST(LongNve, MillionStepsOfLennardJonesDoNotDrift) {
    SystemSpec spec;
    double box_length = 0.0;
    spec.positions = fcc_lattice(kLatticeCells, kDensity, &box_length);
    spec.box = {box_length, box_length, box_length};
    spec.velocities = thermal_velocities(spec.positions.size(), kInitialTemperature, 1);
    spec.force_field = lennard_jones_force_field(1.0, 2.5, 1.12, true);
    spec.integrator = velocity_verlet(kTimeStep);
    spec.steps = kSteps;
    structmd_sim* raw = nullptr;
    ASSERT_EQ(structmd_create("{\"backend\": \"cpu\", \"precision\": \"double\", \"threads\": 1, \"log\": \"quiet\"}", &raw),
              STRUCTMD_OK)
        << structmd_last_error(nullptr);
    SimHandle sim(raw);
    ASSERT_STRUCTMD_OK(sim.get(), structmd_load_string(sim.get(), input_document(spec).dump().c_str()));
    const std::int64_t n = particle_count(sim.get());
    const double lattice_potential = read_energy(sim.get(), "potential") / n;

    const auto start = std::chrono::steady_clock::now();
    std::vector<double> times, totals;
    double potential_sum = 0.0;
    for (std::int64_t step = 0; step <= kSteps; step += kStepsPerSample) {
        if (step > 0) ASSERT_STRUCTMD_OK(sim.get(), structmd_step(sim.get(), kStepsPerSample));
        const double total = read_energy(sim.get(), "total") / n;
        ASSERT_TRUE(std::isfinite(total)) << "step " << step;
        times.push_back(step * kTimeStep);
        totals.push_back(total);
        potential_sum += read_energy(sim.get(), "potential") / n;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double slope = fitted_slope(times, totals);
    const double mean_potential = potential_sum / times.size();
    std::printf("[ measured ] %lld steps of %lld particles in %.1f s: drift %.3e per tau per particle (%.3e over the "
                "run; bound %.1e per tau), potential %.3f -> mean %.3f per particle\n",
                static_cast<long long>(kSteps), static_cast<long long>(n), seconds, slope, slope * times.back(),
                kMaxDriftRate, lattice_potential, mean_potential);
    EXPECT_GT(mean_potential - lattice_potential, kMinPotentialRise) << "the particles hardly moved";
    EXPECT_LT(std::abs(slope), kMaxDriftRate);
}

}  // namespace
}  // namespace structmd_stability
