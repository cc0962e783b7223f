// Throughput of the classic Lennard-Jones liquid (the system of LAMMPS's bench/in.lj, see
// lj_liquid.hpp: fcc at density 0.8442, T = 1.44, LJ cut at 2.5 sigma, 0.3 sigma neighbour skin,
// NVE velocity Verlet with dt = 0.005), driven through the public C API.
//
//   structmd_lj_benchmark [--n N]... [--backend B]... [--precision P]... [--seconds T | --steps S]
//                         [--repeats R] [--warmup W] [--threads K] [--pair F]... [--scene S]...
//                         [--skin D] [--csv PATH]
//   structmd_lj_benchmark [--n N] [--pair F] [--scene S] [--skin D] --write-input PATH
//
// --write-input writes the input of the first scene, pair form and N to PATH and times nothing, so
// the same system can run under the launcher or a profiler.
//
// --pair builtin (the default) runs LJ as LennardJonesType1; --pair expression runs the same
// potential as ["NonBonded","Expression"] (compiled at load time on CUDA, interpreted on the CPU).
//
// --scene lj (the default) is the liquid of N particles; --scene batches is N / 500 independent
// liquids of 500 particles (4 x 5^3) as batches of one input; --scene chains is a melt of N / 100
// chains of 100 beads (rounded to a square number of chains; lj_liquid.hpp's BeadChains: harmonic
// bonds, KratkyPorod angles, WCA between non-bonded pairs, Langevin BBK, dt = 0.005).
// --skin (default 0.3 sigma) is the Verlet list's skin in every scene.
//
// For every (backend, precision, pair form, N) the program builds the input in memory, loads a fresh system,
// takes W untimed steps (first neighbour-list build, caches, GPU clocks), then times R calls of
// structmd_step(S) and reports the median rate. The neighbour-list builds and the device memory come
// from structmd_get_counters: the builds over the R timed calls per 1000 steps, the memory held by
// the handle's buffers after them ("-" if this engine does not report device_memory_bytes).
//
// Steps per timed call: with --steps, S. Otherwise (the default) S is chosen so one call takes about
// T seconds (--seconds, default 0.5): after the warm-up, untimed probe calls of 1, 2, 4, ... steps
// run until one takes at least T/10, and S = T x that call's rate. On a GPU a 16,000,000-particle
// system (tens of steps/s) then runs some tens of steps per call and a 4,000-particle one (thousands
// of steps/s) some thousands, so every size gets the same wall time and the same timer resolution.
// The schedule is made long enough never to end.
//
// Setup (building the text and structmd_load_string) is reported too, untimed: the engine takes its
// input as JSON only, so a 16M-particle run hands it 0.9 GB of text (about a minute to parse).
//
// The table goes to standard output; --csv PATH also writes its rows as CSV (columns: n, backend,
// precision, steps_per_call, steps_per_second, particle_steps_per_second, list_builds_per_1000_steps,
// device_memory_mib (empty when not reported), setup_seconds, pair). setup_seconds includes the
// compilation of an expression. Exit status is non-zero if any
// configuration failed; its row says why and the others still run.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <optional>
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

constexpr double kTimeStep = 0.005;
// The run is ended by this program, never by the schedule.
constexpr int64_t kUnendingSchedule = 1'000'000'000'000;

struct BenchmarkOptions {
    std::vector<int64_t> sizes{32000};
    std::vector<std::string> backends{"auto"};
    std::vector<std::string> precisions{"single"};
    double secondsPerCall = 0.5;
    int64_t fixedSteps = 0;  // 0: adapt to secondsPerCall
    int repeats = 5;
    int64_t warmup = 100;
    int threads = 0;  // 0: the engine's default
    std::vector<std::string> pairForms{"builtin"};
    std::vector<std::string> scenes{"lj"};
    std::vector<std::string> traversals{"auto"};
    double skin = 0.3;  // sigma, added to the cutoff for the Verlet list
    std::string csvPath;
    std::string inputPath;  // write the first scene's input here instead of timing anything
};

struct Row {
    int64_t particles = 0;
    std::string backend;
    std::string precision;
    int64_t stepsPerCall = 0;
    double stepsPerSecond = 0;
    double listBuildsPer1000Steps = 0;
    std::optional<double> deviceMemoryMiB;
    double setupSeconds = 0;
    std::string pairForm;
    std::string scene;
    std::string traversal;
};

constexpr int64_t kBatchCells = 5;      // fcc cells per edge of one batch: 500 particles
constexpr int64_t kBeadsPerChain = 100;

// The input of a scene of about `size` particles.
std::string scene_input(const std::string& scene, int64_t size, const std::string& pairForm, double skin) {
    if (scene == "chains") {
        BeadChains melt;
        const auto rows = std::max<int64_t>(1, std::llround(std::sqrt(static_cast<double>(size) / kBeadsPerChain)));
        melt.chains = rows * rows;
        melt.beads = kBeadsPerChain;
        melt.timeStep = kTimeStep;
        melt.skin = skin;
        melt.scheduleSteps = kUnendingSchedule;
        return bead_chains_input(melt);
    }
    LjLiquid liquid;
    if (scene == "batches") {
        liquid.cells = kBatchCells;
        liquid.batches = std::max<int64_t>(1, std::llround(static_cast<double>(size) / (4 * kBatchCells * kBatchCells * kBatchCells)));
    } else {
        liquid.cells = cells_per_edge(size);
    }
    liquid.timeStep = kTimeStep;
    liquid.skin = skin;
    liquid.scheduleSteps = kUnendingSchedule;
    liquid.asExpression = pairForm == "expression";
    return lj_liquid_input(liquid);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Seconds taken by structmd_step(steps). structmd_step returns once the backend has finished the
// steps (every call ends by reading the numerical-fault flag back from the device, a synchronising
// copy), so the wall time around it is the time of the steps.
double timed_steps(structmd_sim* sim, int64_t steps) {
    const auto start = std::chrono::steady_clock::now();
    check(structmd_step(sim, steps), sim, "structmd_step");
    return seconds_since(start);
}

// Steps per timed call so that one call takes about seconds_per_call (see the header comment).
int64_t probe_steps_per_call(structmd_sim* sim, double seconds_per_call) {
    int64_t steps = 1;
    double seconds = timed_steps(sim, steps);
    while (seconds < 0.1 * seconds_per_call) {
        steps *= 2;
        seconds = timed_steps(sim, steps);
    }
    return std::max<int64_t>(1, std::llround(seconds_per_call * static_cast<double>(steps) / seconds));
}

Row measure(const BenchmarkOptions& options, int64_t requested_size, const std::string& backend,
            const std::string& precision, const std::string& pairForm, const std::string& scene,
            const std::string& traversal) {
    const auto setup_start = std::chrono::steady_clock::now();
    Handle simulation(create_options(backend, precision, options.threads, traversal));
    structmd_sim* sim = simulation.get();
    {
        const std::string input = scene_input(scene, requested_size, pairForm, options.skin);  // released before stepping
        check(structmd_load_string(sim, input.c_str()), sim, "structmd_load_string");
    }
    Row row;
    row.setupSeconds = seconds_since(setup_start);
    row.pairForm = pairForm;
    row.scene = scene;
    row.traversal = traversal;

    check(structmd_step(sim, options.warmup), sim, "structmd_step (warm-up)");
    row.stepsPerCall =
        options.fixedSteps > 0 ? options.fixedSteps : probe_steps_per_call(sim, options.secondsPerCall);

    const nlohmann::json counters_before = engine_counters(sim);
    std::vector<double> rates;
    for (int repeat = 0; repeat < options.repeats; ++repeat)
        rates.push_back(static_cast<double>(row.stepsPerCall) / timed_steps(sim, row.stepsPerCall));
    const nlohmann::json counters_after = engine_counters(sim);

    const auto timed_total = static_cast<double>(row.stepsPerCall) * options.repeats;
    const auto builds = counters_after.at("neighbour_list_builds").get<double>() -
                        counters_before.at("neighbour_list_builds").get<double>();
    row.listBuildsPer1000Steps = 1000.0 * builds / timed_total;
    if (counters_after.contains("device_memory_bytes"))
        row.deviceMemoryMiB = counters_after.at("device_memory_bytes").get<double>() / (1024.0 * 1024.0);

    const nlohmann::json info = engine_info(sim);
    row.particles = info.at("particles").get<int64_t>();
    row.backend = info.at("backend").get<std::string>();
    row.precision = info.at("precision").get<std::string>();
    row.stepsPerSecond = median(rates);
    return row;
}

void print_header() {
    std::printf("%10s  %-7s  %-9s  %10s  %10s  %16s  %14s  %10s  %7s  %-10s  %-6s  %s\n", "N", "backend", "precision",
                "steps/call", "steps/s", "particle-steps/s", "builds/1000st", "memory MiB", "setup s", "pair", "scene",
                "traversal");
}

void print_row(const Row& row) {
    char memory[32] = "-";
    if (row.deviceMemoryMiB) std::snprintf(memory, sizeof memory, "%.1f", *row.deviceMemoryMiB);
    std::printf("%10lld  %-7s  %-9s  %10lld  %10.4g  %16.4g  %14.2f  %10s  %7.2f  %-10s  %-6s  %s\n",
                static_cast<long long>(row.particles), row.backend.c_str(), row.precision.c_str(),
                static_cast<long long>(row.stepsPerCall), row.stepsPerSecond,
                row.stepsPerSecond * static_cast<double>(row.particles), row.listBuildsPer1000Steps, memory,
                row.setupSeconds, row.pairForm.c_str(), row.scene.c_str(), row.traversal.c_str());
}

void write_csv_row(std::ofstream& csv, const Row& row) {
    char line[512];
    char memory[32] = "";
    if (row.deviceMemoryMiB) std::snprintf(memory, sizeof memory, "%.3f", *row.deviceMemoryMiB);
    std::snprintf(line, sizeof line, "%lld,%s,%s,%lld,%.6g,%.6g,%.4f,%s,%.3f,%s,%s,%s\n",
                  static_cast<long long>(row.particles), row.backend.c_str(), row.precision.c_str(),
                  static_cast<long long>(row.stepsPerCall), row.stepsPerSecond,
                  row.stepsPerSecond * static_cast<double>(row.particles), row.listBuildsPer1000Steps, memory,
                  row.setupSeconds, row.pairForm.c_str(), row.scene.c_str(), row.traversal.c_str());
    csv << line << std::flush;
}

}  // namespace

int main(int argc, char** argv) {
    BenchmarkOptions options;
    CLI::App app{"Lennard-Jones liquid throughput over the structmd C API"};
    app.add_option("--n", options.sizes, "Particle counts, rounded to 4 k^3 (repeatable)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--backend", options.backends, "auto, cpu or cuda (repeatable)")
        ->check(CLI::IsMember({"auto", "cpu", "cuda"}))
        ->capture_default_str();
    app.add_option("--precision", options.precisions, "single, mixed or double (repeatable)")
        ->check(CLI::IsMember({"single", "mixed", "double"}))
        ->capture_default_str();
    auto* seconds = app.add_option("--seconds", options.secondsPerCall,
                                   "Target wall time of one timed call; steps per call follow from a probe")
                        ->check(CLI::PositiveNumber)
                        ->capture_default_str();
    app.add_option("--steps", options.fixedSteps, "Fixed steps per timed call instead of --seconds")
        ->check(CLI::PositiveNumber)
        ->excludes(seconds);
    app.add_option("--repeats", options.repeats, "Timed calls (the median is reported)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--warmup", options.warmup, "Untimed steps before the timed calls")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_option("--threads", options.threads, "CPU threads (default: all OpenMP offers)")
        ->check(CLI::PositiveNumber);
    app.add_option("--pair", options.pairForms, "builtin or expression: the form of the LJ potential (repeatable)")
        ->check(CLI::IsMember({"builtin", "expression"}))
        ->capture_default_str();
    app.add_option("--scene", options.scenes, "lj, batches or chains: what runs (repeatable)")
        ->check(CLI::IsMember({"lj", "batches", "chains"}))
        ->capture_default_str();
    app.add_option("--traversal", options.traversals,
                   "auto, clusters or particles: the engine option pair_traversal (repeatable)")
        ->check(CLI::IsMember({"auto", "clusters", "particles"}))
        ->capture_default_str();
    app.add_option("--skin", options.skin, "Neighbour-list skin (sigma)")->check(CLI::PositiveNumber)->capture_default_str();
    app.add_option("--csv", options.csvPath, "Also write the rows to this CSV file");
    app.add_option("--write-input", options.inputPath,
                   "Write the input of the first --scene, --pair and --n to this file and time nothing (to run the "
                   "same system with the launcher or a profiler)");
    CLI11_PARSE(app, argc, argv);

    if (!options.inputPath.empty()) {
        std::ofstream input(options.inputPath);
        input << scene_input(options.scenes.front(), options.sizes.front(), options.pairForms.front(), options.skin);
        if (!input.flush()) {
            std::fprintf(stderr, "cannot write %s\n", options.inputPath.c_str());
            return 2;
        }
        return 0;
    }

    std::ofstream csv;
    if (!options.csvPath.empty() &&
        !open_csv(csv, options.csvPath,
                  "n,backend,precision,steps_per_call,steps_per_second,particle_steps_per_second,"
                  "list_builds_per_1000_steps,device_memory_mib,setup_seconds,pair,scene,traversal"))
        return 2;

    if (options.fixedSteps > 0)
        std::printf("structmd %s, %lld steps per call", structmd_version(),
                    static_cast<long long>(options.fixedSteps));
    else
        std::printf("structmd %s, steps per call chosen for %.3g s", structmd_version(),
                    options.secondsPerCall);
    std::printf(" x %d calls (median), %lld warm-up steps\n", options.repeats, static_cast<long long>(options.warmup));
    print_header();
    std::fflush(stdout);

    int failures = 0;
    for (const auto& scene : options.scenes)
    for (const auto& backend : options.backends)
        for (const auto& precision : options.precisions)
            for (const auto& pairForm : options.pairForms)
            for (const auto& traversal : options.traversals)
            for (const int64_t size : options.sizes) {
                if (scene == "chains" && pairForm != "builtin") continue;  // the melt has no LJ to rewrite
                try {
                    const Row row = measure(options, size, backend, precision, pairForm, scene, traversal);
                    print_row(row);
                    if (csv.is_open()) write_csv_row(csv, row);
                } catch (const Failure& failure) {
                    ++failures;
                    std::printf("%10lld  %-7s  %-9s  failed: %s (status %d)\n", static_cast<long long>(size),
                                backend.c_str(), precision.c_str(), failure.what(), static_cast<int>(failure.status()));
                } catch (const std::exception& error) {
                    ++failures;
                    std::printf("%10lld  %-7s  %-9s  failed: %s\n", static_cast<long long>(size), backend.c_str(),
                                precision.c_str(), error.what());
                }
                std::fflush(stdout);
            }
    return failures == 0 ? 0 : 1;
}
