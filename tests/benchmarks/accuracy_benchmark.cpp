// Accuracy against time for the Lennard-Jones liquid of lj_liquid.hpp (fcc at density 0.8442,
// T = 1.44, LJ cut at 2.5 sigma and shifted so the energy is continuous at the cutoff, NVE velocity
// Verlet), over precision x time step x neighbour skin, driven through the public C API.
//
//   structmd_accuracy_benchmark [--n N] [--backend B] [--precision P]... [--dt DT]... [--skin S]...
//                               [--steps S] [--samples K] [--equilibrate T] [--threads K] [--csv PATH]
//
// Defaults: N = 4,000 (4,000 exactly: 10^3 fcc cells), precision single, mixed and double, dt 0.001,
// 0.002, 0.005 and 0.01, skin 0.1, 0.2, 0.3 and 0.5, 100,000 steps, 100 energy samples. For each
// (precision, dt, skin) the program loads a fresh system and
// 1. equilibrates, untimed, for T time units (--equilibrate, default 10 tau: 2,000 steps at
//    dt = 0.005) with the run's own dt and skin. The lattice melts within the first few tau (the
//    temperature falls from 1.44 to about 0.7 as potential energy rises); the fit below then sees the
//    liquid, not that transient;
// 2. runs the given steps in K equal calls of structmd_step, timing only those calls, and reads the
//    total energy after each (an energy evaluation on those steps only, outside the timing);
// 3. reports
//    - steps/s over the timed calls, and time per tau = 1 / (steps/s x dt), the wall seconds one
//      unit of simulated time costs;
//    - the energy drift: the slope of a least-squares line through total energy per particle against
//      simulated time, in epsilon / tau per particle (signed);
//    - the relative RMS force error sqrt(sum |F - F_ref|^2 / sum |F_ref|^2), summed over particles
//      at 5 points of the run (its start, quarters and end): F from structmd_get_forces, the run's
//      own forces (its Verlet list, its precision); F_ref evaluated here, on the host, in double,
//      from the positions read at the same point, by an exact cell search with the minimum image.
//      A stale neighbour list (too small a skin) shows up here as well as in the drift;
//    - neighbour-list builds per 1000 steps, from structmd_get_counters.
//
// A configuration that fails (a precision this engine does not offer, a blow-up at a large dt)
// prints a line with the library's message and the others still run; the exit status is then 1.
// The table goes to standard output; --csv PATH writes its rows as CSV, columns: precision, dt,
// skin, n, backend, steps, steps_per_second, seconds_per_tau, energy_drift, relative_force_error,
// list_builds_per_1000_steps.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "lj_liquid.hpp"
#include "structmd.hpp"

namespace {

using namespace structmd::benchmarks;
using structmd::host::check;
using structmd::host::Failure;
using structmd::host::Handle;

constexpr int kForceCheckIntervals = 4;  // forces are compared at the start, the quarters and the end

struct AccuracyOptions {
    int64_t size = 4000;
    std::string backend = "auto";
    std::vector<std::string> precisions{"single", "mixed", "double"};
    std::vector<double> timeSteps{0.001, 0.002, 0.005, 0.01};
    std::vector<double> skins{0.1, 0.2, 0.3, 0.5};
    int64_t steps = 100000;
    int64_t samples = 100;
    double equilibrationTime = 10.0;
    int threads = 0;  // 0: the engine's default
    std::string csvPath;
};

struct Row {
    std::string precision;
    double timeStep = 0;
    double skin = 0;
    int64_t particles = 0;
    std::string backend;
    int64_t steps = 0;
    double stepsPerSecond = 0;
    double energyDrift = 0;         // epsilon / tau per particle
    double relativeForceError = 0;
    double listBuildsPer1000Steps = 0;

    double secondsPerTau() const { return 1.0 / (stepsPerSecond * timeStep); }
};

// The LJ force in double: F_i = sum_j 24 (2 r^-12 - r^-6) / r^2 (r_i - r_j) over every j with
// minimum-image distance r < kCutOff (epsilon = sigma = 1). Cells of edge >= kCutOff, so each
// particle's partners lie in its own and the adjacent cells; with fewer than 3 cells along an axis
// the adjacent cells repeat and are visited once. The cutoff is shorter than half the box (the
// engine checks that at load), so the minimum image is the only image within reach.
std::vector<double> reference_forces(const std::vector<double>& xyz, const double box[3]) {
    const size_t count = xyz.size() / 3;
    int cells[3];
    for (int axis = 0; axis < 3; ++axis) cells[axis] = std::max(1, static_cast<int>(box[axis] / kCutOff));

    auto cell_along = [&](double x, int axis) {
        const auto c = static_cast<int>(std::floor((x / box[axis] + 0.5) * cells[axis]));
        return std::clamp(c, 0, cells[axis] - 1);  // positions are wrapped into [-L/2, L/2)
    };
    auto cell_index = [&](int cx, int cy, int cz) { return (static_cast<size_t>(cz) * cells[1] + cy) * cells[0] + cx; };

    // Particles sorted by cell (a counting sort): those of cell c are members[first[c] .. first[c+1]).
    const size_t cell_count = static_cast<size_t>(cells[0]) * cells[1] * cells[2];
    std::vector<size_t> cell_of(count), first(cell_count + 1, 0), members(count);
    for (size_t i = 0; i < count; ++i) {
        cell_of[i] = cell_index(cell_along(xyz[3 * i], 0), cell_along(xyz[3 * i + 1], 1), cell_along(xyz[3 * i + 2], 2));
        ++first[cell_of[i] + 1];
    }
    for (size_t c = 0; c < cell_count; ++c) first[c + 1] += first[c];
    std::vector<size_t> fill(first.begin(), first.end() - 1);
    for (size_t i = 0; i < count; ++i) members[fill[cell_of[i]]++] = i;

    // The distinct cells at offsets -1, 0, +1 from cell c along an axis of n cells, periodically.
    auto adjacent = [](int c, int n) {
        std::vector<int> around;
        for (int offset = -1; offset <= 1; ++offset) {
            const int neighbour = ((c + offset) % n + n) % n;
            if (std::find(around.begin(), around.end(), neighbour) == around.end()) around.push_back(neighbour);
        }
        return around;
    };

    const double cutoff2 = kCutOff * kCutOff;
    std::vector<double> forces(3 * count, 0.0);
    for (size_t i = 0; i < count; ++i) {
        const int cx = cell_along(xyz[3 * i], 0), cy = cell_along(xyz[3 * i + 1], 1), cz = cell_along(xyz[3 * i + 2], 2);
        for (const int nz : adjacent(cz, cells[2]))
            for (const int ny : adjacent(cy, cells[1]))
                for (const int nx : adjacent(cx, cells[0])) {
                    const size_t c = cell_index(nx, ny, nz);
                    for (size_t m = first[c]; m < first[c + 1]; ++m) {
                        const size_t j = members[m];
                        if (j == i) continue;
                        double d[3];
                        for (int axis = 0; axis < 3; ++axis) {
                            d[axis] = xyz[3 * i + axis] - xyz[3 * j + axis];
                            d[axis] -= box[axis] * std::round(d[axis] / box[axis]);
                        }
                        const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
                        if (r2 >= cutoff2) continue;
                        const double inv6 = 1.0 / (r2 * r2 * r2);
                        const double scale = 24.0 * (2.0 * inv6 * inv6 - inv6) / r2;
                        for (int axis = 0; axis < 3; ++axis) forces[3 * i + axis] += scale * d[axis];
                    }
                }
    }
    return forces;
}

// Sums over particles and check points of |F - F_ref|^2 and |F_ref|^2.
struct ForceErrorSums {
    double difference2 = 0;
    double reference2 = 0;

    void add(structmd_sim* sim, int64_t particles) {
        std::vector<double> xyz(3 * static_cast<size_t>(particles)), forces(xyz.size());
        double box[3];
        check(structmd_get_positions(sim, xyz.data(), particles), sim, "structmd_get_positions");
        check(structmd_get_forces(sim, forces.data(), particles), sim, "structmd_get_forces");
        check(structmd_get_box(sim, box), sim, "structmd_get_box");
        const std::vector<double> reference = reference_forces(xyz, box);
        for (size_t k = 0; k < forces.size(); ++k) {
            difference2 += (forces[k] - reference[k]) * (forces[k] - reference[k]);
            reference2 += reference[k] * reference[k];
        }
    }
    double relative() const { return std::sqrt(difference2 / reference2); }
};

// Least-squares slope of y against x.
double fitted_slope(const std::vector<double>& x, const std::vector<double>& y) {
    const double n = static_cast<double>(x.size());
    double mean_x = 0, mean_y = 0;
    for (size_t k = 0; k < x.size(); ++k) {
        mean_x += x[k] / n;
        mean_y += y[k] / n;
    }
    double covariance = 0, variance = 0;
    for (size_t k = 0; k < x.size(); ++k) {
        covariance += (x[k] - mean_x) * (y[k] - mean_y);
        variance += (x[k] - mean_x) * (x[k] - mean_x);
    }
    return covariance / variance;
}

double total_energy(structmd_sim* sim) {
    double energy = 0;
    check(structmd_get_energy(sim, "total", &energy), sim, "structmd_get_energy");
    return energy;
}

double simulated_time(structmd_sim* sim) {
    double time = 0;
    check(structmd_get_time(sim, &time), sim, "structmd_get_time");
    return time;
}

Row run(const AccuracyOptions& options, const std::string& precision, double time_step, double skin) {
    Handle simulation(create_options(options.backend, precision, options.threads));
    structmd_sim* sim = simulation.get();
    const int64_t equilibration_steps = std::llround(options.equilibrationTime / time_step);
    LjLiquid liquid;
    liquid.cells = cells_per_edge(options.size);
    liquid.timeStep = time_step;
    liquid.skin = skin;
    liquid.shiftEnergy = true;
    liquid.scheduleSteps = equilibration_steps + options.steps;
    check(structmd_load_string(sim, lj_liquid_input(liquid).c_str()), sim, "structmd_load_string");
    check(structmd_step(sim, equilibration_steps), sim, "structmd_step (equilibration)");

    int64_t particles = 0;
    check(structmd_get_num_particles(sim, &particles), sim, "structmd_get_num_particles");
    const int64_t samples = std::min(options.samples, options.steps);

    std::vector<double> times{simulated_time(sim)};
    std::vector<double> energies{total_energy(sim) / static_cast<double>(particles)};
    ForceErrorSums force_error;
    force_error.add(sim, particles);
    const nlohmann::json counters_before = engine_counters(sim);

    double stepping_seconds = 0;
    int64_t steps_done = 0;
    int next_force_check = 1;
    for (int64_t sample = 1; sample <= samples; ++sample) {
        const int64_t steps_to_sample = sample * options.steps / samples - steps_done;
        const auto start = std::chrono::steady_clock::now();
        check(structmd_step(sim, steps_to_sample), sim, "structmd_step");
        stepping_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        steps_done += steps_to_sample;
        times.push_back(simulated_time(sim));
        energies.push_back(total_energy(sim) / static_cast<double>(particles));
        if (sample * kForceCheckIntervals >= next_force_check * samples) {
            force_error.add(sim, particles);
            ++next_force_check;
        }
    }
    const nlohmann::json counters_after = engine_counters(sim);

    Row row;
    const nlohmann::json info = engine_info(sim);
    row.precision = info.at("precision").get<std::string>();
    row.backend = info.at("backend").get<std::string>();
    row.timeStep = time_step;
    row.skin = skin;
    row.particles = particles;
    row.steps = options.steps;
    row.stepsPerSecond = static_cast<double>(options.steps) / stepping_seconds;
    row.energyDrift = fitted_slope(times, energies);
    row.relativeForceError = force_error.relative();
    const auto builds = counters_after.at("neighbour_list_builds").get<double>() -
                        counters_before.at("neighbour_list_builds").get<double>();
    row.listBuildsPer1000Steps = 1000.0 * builds / static_cast<double>(options.steps);
    return row;
}

void print_header() {
    std::printf("%-9s  %6s  %5s  %8s  %-7s  %9s  %10s  %10s  %12s  %11s  %13s\n", "precision", "dt", "skin", "N",
                "backend", "steps", "steps/s", "s per tau", "drift e/t/N", "force error", "builds/1000st");
}

void print_row(const Row& row) {
    std::printf("%-9s  %6g  %5g  %8lld  %-7s  %9lld  %10.4g  %10.4g  %12.3e  %11.3e  %13.2f\n", row.precision.c_str(),
                row.timeStep, row.skin, static_cast<long long>(row.particles), row.backend.c_str(),
                static_cast<long long>(row.steps), row.stepsPerSecond, row.secondsPerTau(), row.energyDrift,
                row.relativeForceError, row.listBuildsPer1000Steps);
}

void write_csv_row(std::ofstream& csv, const Row& row) {
    char line[512];
    std::snprintf(line, sizeof line, "%s,%g,%g,%lld,%s,%lld,%.6g,%.6g,%.6e,%.6e,%.4f\n", row.precision.c_str(),
                  row.timeStep, row.skin, static_cast<long long>(row.particles), row.backend.c_str(),
                  static_cast<long long>(row.steps), row.stepsPerSecond, row.secondsPerTau(), row.energyDrift,
                  row.relativeForceError, row.listBuildsPer1000Steps);
    csv << line << std::flush;
}

}  // namespace

int main(int argc, char** argv) {
    AccuracyOptions options;
    CLI::App app{"Energy drift and force error against time for the LJ liquid over the structmd C API"};
    app.add_option("--n", options.size, "Particle count, rounded to 4 k^3")->check(CLI::PositiveNumber)->capture_default_str();
    app.add_option("--backend", options.backend, "auto, cpu or cuda")
        ->check(CLI::IsMember({"auto", "cpu", "cuda"}))
        ->capture_default_str();
    app.add_option("--precision", options.precisions, "single, mixed or double (repeatable)")
        ->check(CLI::IsMember({"single", "mixed", "double"}))
        ->capture_default_str();
    app.add_option("--dt", options.timeSteps, "Time steps (repeatable)")->check(CLI::PositiveNumber)->capture_default_str();
    app.add_option("--skin", options.skins, "Neighbour-list skins in sigma (repeatable)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--steps", options.steps, "Steps of the fitted run")->check(CLI::PositiveNumber)->capture_default_str();
    app.add_option("--samples", options.samples, "Total-energy samples along the run")
        ->check(CLI::Range(int64_t{2}, int64_t{1} << 40))
        ->capture_default_str();
    app.add_option("--equilibrate", options.equilibrationTime, "Untimed simulated time before the run (tau)")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_option("--threads", options.threads, "CPU threads (default: all OpenMP offers)")->check(CLI::PositiveNumber);
    app.add_option("--csv", options.csvPath, "Also write the rows to this CSV file");
    CLI11_PARSE(app, argc, argv);

    std::ofstream csv;
    if (!options.csvPath.empty() &&
        !open_csv(csv, options.csvPath,
                  "precision,dt,skin,n,backend,steps,steps_per_second,seconds_per_tau,energy_drift,"
                  "relative_force_error,list_builds_per_1000_steps"))
        return 2;

    std::printf("structmd %s, LJ liquid (shifted), %lld steps after %g tau of equilibration, %lld energy samples\n",
                structmd_version(), static_cast<long long>(options.steps), options.equilibrationTime,
                static_cast<long long>(options.samples));
    print_header();
    std::fflush(stdout);

    int failures = 0;
    for (const auto& precision : options.precisions)
        for (const double time_step : options.timeSteps)
            for (const double skin : options.skins) {
                try {
                    const Row row = run(options, precision, time_step, skin);
                    print_row(row);
                    if (csv.is_open()) write_csv_row(csv, row);
                } catch (const Failure& failure) {
                    ++failures;
                    std::printf("%-9s  %6g  %5g  failed: %s (status %d)\n", precision.c_str(), time_step, skin,
                                failure.what(), static_cast<int>(failure.status()));
                } catch (const std::exception& error) {
                    ++failures;
                    std::printf("%-9s  %6g  %5g  failed: %s\n", precision.c_str(), time_step, skin, error.what());
                }
                std::fflush(stdout);
            }
    return failures == 0 ? 0 : 1;
}
