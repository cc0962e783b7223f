// The classic Lennard-Jones liquid benchmark (the system of LAMMPS's bench/in.lj), driven through
// the public C API: an fcc lattice at reduced density 0.8442, T = 1.44, LJ cut at 2.5 sigma with a
// 0.3 sigma neighbour skin, NVE velocity Verlet with dt = 0.005. The input is built in memory.
//
//   structmd_lj_benchmark [--n N]... [--backend B]... [--precision P]... [--steps S] [--repeats R]
//                         [--warmup W] [--threads T]
//
// For every (N, backend, precision) the program loads a fresh system, takes W untimed steps (first
// neighbour-list build, velocity draw, caches, GPU clocks), then times R calls of structmd_step(S)
// and reports the median. Exit status is non-zero if any configuration failed.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "structmd.hpp"

namespace {

using structmd::host::check;
using structmd::host::Failure;
using structmd::host::Handle;

constexpr double kDensity = 0.8442;
constexpr double kTemperature = 1.44;
constexpr double kTimeStep = 0.005;
constexpr double kCutOffFactor = 2.5;  // in sigma
constexpr double kSkin = 0.3;          // in sigma

struct BenchmarkOptions {
    std::vector<int64_t> sizes{32000};
    std::vector<std::string> backends{"auto"};
    std::vector<std::string> precisions{"single"};
    int64_t steps = 500;
    int repeats = 5;
    int64_t warmup = 100;
    int threads = 0;  // 0: the engine's default
};

// fcc holds 4 particles per cubic cell; the nearest k^3 cells to the requested size.
int64_t cells_per_edge(int64_t requested) {
    const auto k = static_cast<int64_t>(std::llround(std::cbrt(static_cast<double>(requested) / 4.0)));
    return std::max<int64_t>(k, 1);
}

void append_format(std::string& out, const char* format, double a, double b, double c) {
    char text[96];
    const int length = std::snprintf(text, sizeof text, format, a, b, c);
    out.append(text, static_cast<size_t>(length));
}

// The whole input document for k^3 fcc cells. No velocity column: the engine draws velocities
// from Maxwell-Boltzmann at the ensemble temperature.
std::string lj_liquid_input(int64_t cells, int64_t total_steps) {
    const double lattice = std::cbrt(4.0 / kDensity);
    const double box = lattice * static_cast<double>(cells);
    const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    const int64_t particles = 4 * cells * cells * cells;

    std::string json;
    json.reserve(static_cast<size_t>(particles) * 80 + 2048);
    json += R"({"system": {"info": {"type": ["Simulation", "Information"],)"
            R"( "parameters": {"name": "lj_benchmark", "seed": 1}}},)";
    json += R"("global": {"units": {"type": ["Units", "None"]},)"
            R"("types": {"type": ["Types", "Basic"], "labels": ["name", "mass", "radius", "charge"],)"
            R"( "data": [["A", 1.0, 0.5, 0.0]]},)"
            R"("ensemble": {"type": ["Ensemble", "NVT"], "labels": ["box", "temperature"], "data": [[)";
    append_format(json, "[%.17g, %.17g, %.17g], ", box, box, box);
    json += std::to_string(kTemperature) + "]]}},";

    json += R"("integrator": {"vv": {"type": ["Verlet", "VelocityVerlet"], "parameters": {"timeStep": )" +
            std::to_string(kTimeStep) + "}},";
    json += R"("schedule": {"type": ["Schedule", "Integrator"], "labels": ["order", "integrator", "steps"],)"
            R"( "data": [[1, "vv", )" + std::to_string(total_steps) + "]]}},";

    // Lattice sites shifted by a quarter cell so none sits on the box boundary at -L/2.
    json += R"("state": {"labels": ["id", "position"], "data": [)";
    int64_t id = 0;
    for (int64_t i = 0; i < cells; ++i)
        for (int64_t j = 0; j < cells; ++j)
            for (int64_t l = 0; l < cells; ++l)
                for (const auto& site : basis) {
                    if (id > 0) json += ',';
                    json += '[' + std::to_string(id) + ", ";
                    append_format(json, "[%.17g, %.17g, %.17g]]",
                                  -0.5 * box + lattice * (static_cast<double>(i) + site[0] + 0.25),
                                  -0.5 * box + lattice * (static_cast<double>(j) + site[1] + 0.25),
                                  -0.5 * box + lattice * (static_cast<double>(l) + site[2] + 0.25));
                    ++id;
                }
    json += "]},";

    json += R"("topology": {"structure": {"labels": ["id", "type"], "data": [)";
    for (int64_t p = 0; p < particles; ++p) json += (p > 0 ? ",[" : "[") + std::to_string(p) + R"(, "A"])";
    json += "]},";
    char factors[160];
    std::snprintf(factors, sizeof factors,
                  R"("parameters": {"cutOffVerletFactor": %.17g}}, )", (kCutOffFactor + kSkin) / kCutOffFactor);
    json += R"("forceField": {"nl": {"type": ["VerletConditionalListSet", "all"], )";
    json += factors;
    json += R"("lj": {"type": ["NonBonded", "LennardJonesType1"],)"
            R"( "parameters": {"cutOffFactor": )" + std::to_string(kCutOffFactor) +
            R"(, "condition": "all"}, "labels": ["name_i", "name_j", "epsilon", "sigma"],)"
            R"( "data": [["A", "A", 1.0, 1.0]]}}}})";
    return json;
}

nlohmann::json engine_info(const structmd_sim* sim) { return nlohmann::json::parse(structmd::host::info(sim)); }

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t half = values.size() / 2;
    return values.size() % 2 == 1 ? values[half] : 0.5 * (values[half - 1] + values[half]);
}

struct Row {
    int64_t particles;
    std::string backend;
    std::string precision;
    double steps_per_second;
};

Row measure(const BenchmarkOptions& options, int64_t requested_size, const std::string& backend,
            const std::string& precision) {
    nlohmann::json create = {{"backend", backend}, {"precision", precision}, {"log", "warning"}};
    if (options.threads > 0) create["threads"] = options.threads;
    Handle simulation(create.dump());
    structmd_sim* sim = simulation.get();

    const int64_t cells = cells_per_edge(requested_size);
    const std::string input = lj_liquid_input(cells, options.warmup + options.repeats * options.steps);
    check(structmd_load_string(sim, input.c_str()), sim, "structmd_load_string");
    check(structmd_step(sim, options.warmup), sim, "structmd_step (warm-up)");

    // structmd_step returns once the device has finished the steps (the engine ends every call by
    // reading its numerical-fault flag back from the device, a synchronising copy), so the wall
    // time around the call is the time of the steps and nothing more.
    std::vector<double> rates;
    for (int repeat = 0; repeat < options.repeats; ++repeat) {
        const auto start = std::chrono::steady_clock::now();
        check(structmd_step(sim, options.steps), sim, "structmd_step");
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        rates.push_back(static_cast<double>(options.steps) / seconds);
    }

    const nlohmann::json info = engine_info(sim);
    return Row{info.at("particles").get<int64_t>(), info.at("backend").get<std::string>(),
               info.at("precision").get<std::string>(), median(rates)};
}

}  // namespace

int main(int argc, char** argv) {
    BenchmarkOptions options;
    CLI::App app{"Lennard-Jones liquid benchmark over the structmd C API"};
    app.add_option("--n", options.sizes, "Particle counts, rounded to 4 k^3 (repeatable)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--backend", options.backends, "auto, cpu or cuda (repeatable)")
        ->check(CLI::IsMember({"auto", "cpu", "cuda"}))
        ->capture_default_str();
    app.add_option("--precision", options.precisions, "single or double (repeatable)")
        ->check(CLI::IsMember({"single", "double"}))
        ->capture_default_str();
    app.add_option("--steps", options.steps, "Steps per timed repeat")->check(CLI::PositiveNumber)->capture_default_str();
    app.add_option("--repeats", options.repeats, "Timed repeats (the median is reported)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--warmup", options.warmup, "Untimed steps before the repeats")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_option("--threads", options.threads, "CPU threads (default: all OpenMP offers)")
        ->check(CLI::PositiveNumber);
    CLI11_PARSE(app, argc, argv);

    std::printf("structmd %s, LJ liquid, %lld steps x %d repeats (median), %lld warm-up steps\n",
                structmd_version(), static_cast<long long>(options.steps), options.repeats,
                static_cast<long long>(options.warmup));
    std::printf("%10s  %-8s  %-9s  %12s  %16s\n", "N", "backend", "precision", "steps/s", "particle-steps/s");
    std::fflush(stdout);

    int failures = 0;
    for (const auto& backend : options.backends)
        for (const auto& precision : options.precisions)
            for (const int64_t size : options.sizes) {
                try {
                    const Row row = measure(options, size, backend, precision);
                    std::printf("%10lld  %-8s  %-9s  %12.5g  %16.5g\n", static_cast<long long>(row.particles),
                                row.backend.c_str(), row.precision.c_str(), row.steps_per_second,
                                row.steps_per_second * static_cast<double>(row.particles));
                } catch (const Failure& failure) {
                    ++failures;
                    std::printf("%10lld  %-8s  %-9s  failed: %s (status %d)\n", static_cast<long long>(size),
                                backend.c_str(), precision.c_str(), failure.what(), static_cast<int>(failure.status()));
                } catch (const std::exception& error) {
                    ++failures;
                    std::printf("%10lld  %-8s  %-9s  failed: %s\n", static_cast<long long>(size), backend.c_str(),
                                precision.c_str(), error.what());
                }
                std::fflush(stdout);
            }
    return failures == 0 ? 0 : 1;
}
