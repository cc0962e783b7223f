// Energy conservation of VelocityVerlet on a Lennard-Jones liquid (CPU backend, double precision).
//
// 500 particles at density 0.8 start on an fcc lattice with Maxwell-Boltzmann velocities at T = 1.44
// and melt; the LJ potential is cut at 2.5 sigma and shifted. The same 10 tau are integrated with
// dt = 0.005 and dt = 0.0025 and the total energy per particle e(t) is sampled every 0.05 tau.
//
// The bounds come from an independent numpy integration of this very system (same initial state,
// all pairs, no neighbour list): at dt = 0.005 it gives max |e(t) - e(0)| = 1.1e-3 (reached while the
// lattice melts), a fitted drift of -1.2e-4 and an rms fluctuation of 1.1e-4 per particle; at
// dt = 0.0025, rms 2.9e-5 (ratio 3.95). The bounds sit 4x to 8x above these values:
// - A missing second half kick gives max |e(t) - e(0)| = 0.97 and a drift of 0.04 per particle in the
//   same numpy run, 250x over the bound.
// - Velocity Verlet is symplectic and second order: its energy error oscillates with an amplitude
//   proportional to dt^2, so halving dt must divide the rms by about 4. A first-order update (one full
//   kick then a drift, velocities reported half a step off) gave max |e(t) - e(0)| = 0.043 over 3 tau
//   and an rms ratio of 1.99 in numpy: it fails both checks.
// - A neighbour list that misses pairs does not show in the energy budget: the energy is evaluated
//   over the same incomplete list, so the truncated dynamics conserves its own energy (a list never
//   rebuilt in 10 tau gave max |e(t) - e(0)| = 1.1e-3, indistinguishable). At every sample, the
//   engine's potential energy and forces are therefore compared with an all-pairs evaluation of its
//   own positions; a missed pair changes them by ~1e-6 and ~1e-4 relative against a 1e-10 tolerance.
// - The potential energy per particle must change by far more than the bound (it rises by ~1 as the
//   lattice melts), otherwise a frozen system would pass.
#include "physics_support.hpp"

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace structmd_physics {
namespace {

constexpr int kCells = 5;  // 4 * 5^3 = 500 particles
constexpr double kDensity = 0.8;
constexpr double kTemperature = 1.44;
constexpr double kDuration = 10.0;
constexpr double kSampleInterval = 0.05;
constexpr double kMaxFluctuation = 5e-3;  // max |e(t) - e(0)| per particle, dt = 0.005
constexpr double kMaxDrift = 1e-3;        // |fitted slope| x duration per particle, dt = 0.005
constexpr double kMinPotentialChange = 0.5;  // per particle; melting the lattice raises it by ~1
constexpr double kAllPairsTolerance = 1e-10;
constexpr double kCutoff = 2.5;

struct Trajectory {
    std::vector<double> total;      // per particle
    std::vector<double> potential;  // per particle
    double max_energy_deviation_from_all_pairs = 0.0;  // relative
    double max_force_deviation_from_all_pairs = 0.0;   // max-relative
};

double lj_energy(double r2) {
    const double inverse_r6 = 1.0 / (r2 * r2 * r2);
    return 4.0 * (inverse_r6 * inverse_r6 - inverse_r6);
}

// Shifted LJ over every pair within the cutoff (minimum image), no neighbour list: the yardstick for
// the engine's list. Returns the potential energy and fills forces.
double all_pairs_lennard_jones(const std::vector<double>& xyz, double box_length, std::vector<double>* forces) {
    const std::size_t n = xyz.size() / 3;
    const double shift = lj_energy(kCutoff * kCutoff);
    forces->assign(xyz.size(), 0.0);
    double energy = 0.0;
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j) {
            double d[3], r2 = 0.0;
            for (int k = 0; k < 3; ++k) {
                d[k] = minimum_image(xyz[3 * j + k] - xyz[3 * i + k], box_length);
                r2 += d[k] * d[k];
            }
            if (r2 >= kCutoff * kCutoff) continue;
            energy += lj_energy(r2) - shift;
            const double inverse_r6 = 1.0 / (r2 * r2 * r2);
            const double du_dr_over_r = -24.0 * (2.0 * inverse_r6 * inverse_r6 - inverse_r6) / r2;
            for (int k = 0; k < 3; ++k) {
                (*forces)[3 * i + k] += du_dr_over_r * d[k];
                (*forces)[3 * j + k] -= du_dr_over_r * d[k];
            }
        }
    return energy;
}

std::string lennard_jones_liquid_input(double time_step) {
    const double lattice = std::cbrt(4.0 / kDensity);
    const double box_length = kCells * lattice;
    const Vec3 basis[4] = {{0.0, 0.0, 0.0}, {0.5, 0.5, 0.0}, {0.5, 0.0, 0.5}, {0.0, 0.5, 0.5}};
    std::vector<Vec3> positions, velocities;
    SplitMix64 rng(2024);
    for (int ix = 0; ix < kCells; ++ix)
        for (int iy = 0; iy < kCells; ++iy)
            for (int iz = 0; iz < kCells; ++iz)
                for (const Vec3& b : basis) {
                    positions.push_back({(ix + b[0]) * lattice - 0.5 * box_length, (iy + b[1]) * lattice - 0.5 * box_length,
                                         (iz + b[2]) * lattice - 0.5 * box_length});
                    velocities.push_back({rng.normal(), rng.normal(), rng.normal()});
                }
    // Zero total momentum, then scale to the exact temperature (3N - 3 degrees of freedom, k_B = m = 1).
    Vec3 mean{0.0, 0.0, 0.0};
    for (const Vec3& v : velocities)
        for (int k = 0; k < 3; ++k) mean[k] += v[k] / velocities.size();
    double twice_kinetic = 0.0;
    for (Vec3& v : velocities)
        for (int k = 0; k < 3; ++k) {
            v[k] -= mean[k];
            twice_kinetic += v[k] * v[k];
        }
    const double scale = std::sqrt(kTemperature * (3.0 * velocities.size() - 3.0) / twice_kinetic);
    for (Vec3& v : velocities)
        for (double& c : v) c *= scale;
    const std::string force_field =
        "\"nl\": {\"type\": [\"VerletConditionalListSet\", \"all\"], \"parameters\": {\"cutOffVerletFactor\": 1.12}},\n"
        "\"lj\": {\"type\": [\"NonBonded\", \"LennardJonesType1\"],\n"
        "       \"parameters\": {\"cutOffFactor\": " + number(kCutoff) + ", \"condition\": \"all\", \"shift\": true},\n"
        "       \"labels\": [\"name_i\", \"name_j\", \"epsilon\", \"sigma\"], \"data\": [[\"A\", \"A\", 1.0, 1.0]]}";
    return input_document(box_length, positions, std::vector<std::string>(positions.size(), "A"), velocities,
                          force_field, time_step);
}

void integrate(double time_step, Trajectory* out) {
    structmd_sim* raw = nullptr;
    ASSERT_EQ(structmd_create(create_options("cpu", "double").c_str(), &raw), STRUCTMD_OK) << structmd_last_error(nullptr);
    SimHandle handle(raw);
    structmd_sim* sim = handle.get();
    ASSERT_STRUCTMD_OK(sim, structmd_load_string(sim, lennard_jones_liquid_input(time_step).c_str()));
    std::int64_t n = 0;
    ASSERT_STRUCTMD_OK(sim, structmd_get_num_particles(sim, &n));
    double box[3];
    ASSERT_STRUCTMD_OK(sim, structmd_get_box(sim, box));
    std::vector<double> xyz(3 * n), forces(3 * n), all_pairs_forces;
    const auto steps_per_sample = static_cast<std::int64_t>(std::llround(kSampleInterval / time_step));
    const auto samples = static_cast<int>(std::llround(kDuration / kSampleInterval));
    for (int s = 0; s <= samples; ++s) {
        if (s > 0) ASSERT_STRUCTMD_OK(sim, structmd_step(sim, steps_per_sample));
        double total = 0.0, potential = 0.0;
        ASSERT_STRUCTMD_OK(sim, structmd_get_energy(sim, "total", &total));
        ASSERT_STRUCTMD_OK(sim, structmd_get_energy(sim, "potential", &potential));
        out->total.push_back(total / n);
        out->potential.push_back(potential / n);

        ASSERT_STRUCTMD_OK(sim, structmd_get_positions(sim, xyz.data(), n));
        ASSERT_STRUCTMD_OK(sim, structmd_get_forces(sim, forces.data(), n));
        const double all_pairs_energy = all_pairs_lennard_jones(xyz, box[0], &all_pairs_forces);
        out->max_energy_deviation_from_all_pairs =
            std::max(out->max_energy_deviation_from_all_pairs, relative_deviation(potential, all_pairs_energy));
        // At s = 0 the perfect lattice has zero net forces: a relative measure is meaningless there.
        if (s > 0)
            out->max_force_deviation_from_all_pairs =
                std::max(out->max_force_deviation_from_all_pairs, max_relative_deviation(forces, all_pairs_forces));
    }
}

double max_deviation_from_start(const std::vector<double>& e) {
    double m = 0.0;
    for (double x : e) m = std::max(m, std::abs(x - e.front()));
    return m;
}

// Least-squares slope of e against sample index, times the run's length: the systematic change.
double fitted_drift(const std::vector<double>& e) {
    const double count = static_cast<double>(e.size());
    double mean_t = 0.0, mean_e = 0.0;
    for (std::size_t i = 0; i < e.size(); ++i) {
        mean_t += i / count;
        mean_e += e[i] / count;
    }
    double covariance = 0.0, variance = 0.0;
    for (std::size_t i = 0; i < e.size(); ++i) {
        covariance += (i - mean_t) * (e[i] - mean_e);
        variance += (i - mean_t) * (i - mean_t);
    }
    return covariance / variance * (count - 1.0);
}

// Root mean square of e about its own mean: the shadow-Hamiltonian oscillation.
double rms_fluctuation(const std::vector<double>& e) {
    double mean = 0.0;
    for (double x : e) mean += x / e.size();
    double sum = 0.0;
    for (double x : e) sum += (x - mean) * (x - mean);
    return std::sqrt(sum / e.size());
}

TEST(NveConservation, LennardJonesLiquidVelocityVerlet) {
    const auto start = std::chrono::steady_clock::now();
    Trajectory coarse, fine;
    ASSERT_NO_FATAL_FAILURE(integrate(0.005, &coarse));
    ASSERT_NO_FATAL_FAILURE(integrate(0.0025, &fine));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    const double fluctuation = max_deviation_from_start(coarse.total);
    const double drift = fitted_drift(coarse.total);
    const double rms_ratio = rms_fluctuation(coarse.total) / rms_fluctuation(fine.total);
    const double potential_change = max_deviation_from_start(coarse.potential);
    std::printf("[ measured ] dt 0.005: max |e - e0| %.3e, drift %.3e, rms %.3e per particle; dt 0.0025: max |e - e0| "
                "%.3e, rms %.3e; rms ratio %.2f; potential change %.3f per particle; %.1f s\n",
                fluctuation, drift, rms_fluctuation(coarse.total), max_deviation_from_start(fine.total),
                rms_fluctuation(fine.total), rms_ratio, potential_change, seconds);
    std::printf("[ measured ] engine vs all pairs: energy %.3e, forces %.3e (dt 0.005); energy %.3e, forces %.3e "
                "(dt 0.0025)\n",
                coarse.max_energy_deviation_from_all_pairs, coarse.max_force_deviation_from_all_pairs,
                fine.max_energy_deviation_from_all_pairs, fine.max_force_deviation_from_all_pairs);

    EXPECT_GT(potential_change, kMinPotentialChange) << "the system hardly moved";
    EXPECT_LT(fluctuation, kMaxFluctuation);
    EXPECT_LT(std::abs(drift), kMaxDrift);
    EXPECT_LT(max_deviation_from_start(fine.total), kMaxFluctuation / 4.0);
    EXPECT_GT(rms_ratio, 2.8) << "the energy error does not scale as dt^2";
    EXPECT_LT(rms_ratio, 5.7) << "the energy error does not scale as dt^2";
    for (const Trajectory* t : {&coarse, &fine}) {
        EXPECT_LT(t->max_energy_deviation_from_all_pairs, kAllPairsTolerance) << "the neighbour list misses pairs";
        EXPECT_LT(t->max_force_deviation_from_all_pairs, kAllPairsTolerance) << "the neighbour list misses pairs";
    }
}

}  // namespace
}  // namespace structmd_physics
