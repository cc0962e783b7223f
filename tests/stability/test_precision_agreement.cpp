// Single and double precision sample the same thermodynamics on the CUDA backend: a Lennard-Jones
// liquid under Langevin dynamics (Grønbech-Jensen-Farago) gives the same mean potential energy per
// particle, kinetic temperature and pressure in both, within their statistical errors.
//
// 6912 particles (fcc, 12^3 cells) at density 0.8442, bath T = 1.44, friction 1, dt = 0.005,
// Lennard-Jones cut at 2.5 sigma and shifted. Each precision runs 10000 steps of equilibration (the
// lattice melts), then 100000 steps sampled every 100. The samples are grouped into 20 blocks of
// 5000 steps (25 tau, much longer than the ~1 tau correlation time of these quantities with
// friction 1), so block means are independent and the standard error of a run's mean is the
// standard deviation of its block means over sqrt(20). The two runs share the noise seed but
// decorrelate within a few tau (chaos amplifies float rounding), so treating them as independent
// overestimates the error of their difference: the bound |mean_single - mean_double| <
// 4 sqrt(se_single^2 + se_double^2) is then failed by chance rarely: with 20 blocks per run the ratio
// follows a t distribution of ~38 degrees of freedom, beyond 4 with probability ~3e-4 per quantity.
//
// Measured on an H200 (about 5 s per precision): potential energy per particle -4.4816 +- 6e-4
// (single) and -4.4819 +- 7e-4 (double), kinetic temperature 1.4360 +- 6e-4 and 1.4361 +- 4e-4,
// pressure 4.872 +- 3e-3 and 4.871 +- 4e-3. Four combined errors thus resolve about 0.08% of the
// potential energy, 0.2% of the temperature and 0.4% of the pressure: a precision defect that biases
// forces or kicks at that level fails. The test also fails when a standard error comes out above
// about three times these (kMax*Error), so an unexpectedly noisy run cannot pass by a loose bound.
//
// Exits with 77 (skipped for CTest) when no CUDA backend is usable. Usage:
// test_precision_agreement [--backend=cuda|cpu] (cpu runs the same comparison, in hours).
#include "stability_support.hpp"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace structmd_stability {
namespace {

std::string g_backend = "cuda";

constexpr int kLatticeCells = 12;
constexpr double kDensity = 0.8442;
constexpr double kTemperature = 1.44;
constexpr double kTimeStep = 0.005;
constexpr std::int64_t kEquilibrationSteps = 10000;
constexpr std::int64_t kProductionSteps = 100000;
constexpr std::int64_t kStepsPerSample = 100;
constexpr int kBlocks = 20;
constexpr double kCombinedErrors = 4.0;
constexpr double kMaxPotentialError = 2e-3;
constexpr double kMaxTemperatureError = 2e-3;
constexpr double kMaxPressureError = 1e-2;

struct Estimate {
    double mean = 0.0;
    double standard_error = 0.0;
};

Estimate block_average(const std::vector<double>& samples) {
    const std::size_t per_block = samples.size() / kBlocks;
    std::vector<double> means(kBlocks, 0.0);
    for (int b = 0; b < kBlocks; ++b)
        for (std::size_t k = 0; k < per_block; ++k) means[b] += samples[b * per_block + k] / per_block;
    Estimate e;
    for (double m : means) e.mean += m / kBlocks;
    double variance = 0.0;
    for (double m : means) variance += (m - e.mean) * (m - e.mean) / (kBlocks - 1);
    e.standard_error = std::sqrt(variance / kBlocks);
    return e;
}

struct Thermodynamics {
    Estimate potential;    // per particle
    Estimate temperature;  // kinetic, 2K / (3N - 3)
    Estimate pressure;
};

void sample(const std::string& precision, Thermodynamics* out) {
    SystemSpec spec;
    double box_length = 0.0;
    spec.positions = fcc_lattice(kLatticeCells, kDensity, &box_length);
    spec.box = {box_length, box_length, box_length};
    spec.temperature = kTemperature;
    spec.force_field = lennard_jones_force_field(1.0, 2.5, 1.12, true);
    spec.integrator = {{"type", {"Langevin", "GJF"}},
                       {"parameters", {{"timeStep", kTimeStep}, {"frictionConstant", 1.0}}}};
    spec.steps = kEquilibrationSteps + kProductionSteps;
    SimHandle sim = load_document(input_document(spec), g_backend, precision);
    ASSERT_TRUE(sim);
    const std::int64_t n = particle_count(sim.get());
    const auto start = std::chrono::steady_clock::now();
    ASSERT_STRUCTMD_OK(sim.get(), structmd_step(sim.get(), kEquilibrationSteps));
    std::vector<double> potential, temperature, pressure;
    for (std::int64_t step = 0; step < kProductionSteps; step += kStepsPerSample) {
        ASSERT_STRUCTMD_OK(sim.get(), structmd_step(sim.get(), kStepsPerSample));
        potential.push_back(read_energy(sim.get(), "potential") / n);
        temperature.push_back(2.0 * read_energy(sim.get(), "kinetic") / (3.0 * n - 3.0));
        double p = NAN;
        ASSERT_STRUCTMD_OK(sim.get(), structmd_get_pressure(sim.get(), &p));
        pressure.push_back(p);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out->potential = block_average(potential);
    out->temperature = block_average(temperature);
    out->pressure = block_average(pressure);
    std::printf("[ measured ] %s, %lld particles, %.1f s: potential %.5f +- %.1e, temperature %.5f +- %.1e, "
                "pressure %.5f +- %.1e\n",
                precision.c_str(), static_cast<long long>(n), seconds, out->potential.mean,
                out->potential.standard_error, out->temperature.mean, out->temperature.standard_error,
                out->pressure.mean, out->pressure.standard_error);
}

void expect_agreement(const char* quantity, const Estimate& single, const Estimate& twice, double max_error) {
    const double combined = std::hypot(single.standard_error, twice.standard_error);
    EXPECT_LT(std::abs(single.mean - twice.mean), kCombinedErrors * combined)
        << quantity << ": single " << single.mean << ", double " << twice.mean << ", combined error " << combined;
    EXPECT_LT(single.standard_error, max_error) << quantity << ": the single-precision run is too noisy";
    EXPECT_LT(twice.standard_error, max_error) << quantity << ": the double-precision run is too noisy";
}

TEST(PrecisionAgreement, LangevinLennardJonesLiquidSamplesTheSameThermodynamics) {
    Thermodynamics single, twice;
    ASSERT_NO_FATAL_FAILURE(sample("single", &single));
    ASSERT_NO_FATAL_FAILURE(sample("double", &twice));
    expect_agreement("potential energy per particle", single.potential, twice.potential, kMaxPotentialError);
    expect_agreement("kinetic temperature", single.temperature, twice.temperature, kMaxTemperatureError);
    expect_agreement("pressure", single.pressure, twice.pressure, kMaxPressureError);
}

}  // namespace
}  // namespace structmd_stability

int main(int argc, char** argv) {
    return structmd_stability::run_tests_on_backend(argc, argv, structmd_stability::g_backend, "single");
}
