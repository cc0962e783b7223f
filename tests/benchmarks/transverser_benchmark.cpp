// The cost of a transverser against a built-in pair term over the same liquid (issue 35: a user's
// traversal must run as fast as a built-in pair term over the same list, within 1.2x). The LJ
// liquid of lj_liquid.hpp (cut at 2.5 sigma), driven through the public C API:
//
//   structmd_transverser_benchmark [--n N]... [--backend B]... [--precision P]... [--calls C]
//                                  [--repeats R] [--warmup W] [--threads K] [--csv PATH]
//
// Each form is timed as C calls of "structmd_step(sim, 1) + the form", so that every call sees new
// positions (no cached result is reused, and each list follows the particles as it does in a run:
// refreshed every step, rebuilt when some particle moved half its skin), the median of R such
// samples reported per call, less the median of C bare steps (the "baseline" row):
//   builtin_energy       structmd_compute(STRUCTMD_ENERGY): the LennardJonesType1 pair kernel for
//                        per-particle energies alone (the step made the forces)
//   builtin_energy_read  the same, then structmd_get_particle_energies: n values to the host
//   expression_lj        structmd_traverse_expression("4 * (r^-12 - r^-6)", 2.5): the LJ energy as
//                        an expression transverser over its own list (skin 0.25 against the
//                        liquid's 0.3), compiled by NVRTC on CUDA, interpreted on the CPU; it
//                        copies its n sums to the host, as builtin_energy_read does
//   expression_count     structmd_traverse_expression("r < 1.5", 2.5): neighbour counts, same list
// ratio: the form's net time over builtin_energy_read's (a pair term's scalar per particle, computed
// and handed to the host, as a transverser's is). The CSV columns: n, backend, precision, form,
// seconds_per_call, ratio_to_builtin.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <functional>
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

struct Options {
    std::vector<int64_t> sizes{32000};
    std::vector<std::string> backends{"auto"};
    std::vector<std::string> precisions{"single"};
    int calls = 50;
    int repeats = 5;
    int warmup = 5;
    int threads = 0;
    std::string csvPath;
};

struct Row {
    int64_t particles;
    std::string backend, precision, form;
    double secondsPerCall;
    double ratio;
};

double median_seconds_per_call(const Options& options, const std::function<void()>& call) {
    for (int k = 0; k < options.warmup; ++k) call();
    std::vector<double> samples;
    for (int repeat = 0; repeat < options.repeats; ++repeat) {
        const auto start = std::chrono::steady_clock::now();
        for (int k = 0; k < options.calls; ++k) call();
        samples.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() /
                          options.calls);
    }
    return median(samples);
}

std::vector<Row> measure(const Options& options, int64_t size, const std::string& backend,
                         const std::string& precision) {
    Handle simulation(create_options(backend, precision, options.threads));
    structmd_sim* sim = simulation.get();
    LjLiquid liquid;
    liquid.cells = cells_per_edge(size);
    liquid.scheduleSteps = 1'000'000'000;
    check(structmd_load_string(sim, lj_liquid_input(liquid).c_str()), sim, "structmd_load_string");
    check(structmd_step(sim, 20), sim, "structmd_step");  // melt the lattice a little
    int64_t n = 0;
    check(structmd_get_num_particles(sim, &n), sim, "structmd_get_num_particles");
    std::vector<double> energies(n), sums(n);
    const auto step = [&] { check(structmd_step(sim, 1), sim, "structmd_step"); };
    const auto traverse = [&](const char* compute) {
        step();
        check(structmd_traverse_expression(sim, compute, kCutOff, sums.data(), n), sim, "structmd_traverse_expression");
    };
    const auto energy = [&] {
        step();
        check(structmd_compute(sim, STRUCTMD_ENERGY), sim, "structmd_compute");
    };

    const double baseline = median_seconds_per_call(options, step);
    struct Form {
        const char* name;
        std::function<void()> call;
    };
    const std::vector<Form> forms = {
        {"builtin_energy", energy},
        {"builtin_energy_read",
         [&] {
             energy();
             check(structmd_get_particle_energies(sim, energies.data(), n), sim, "structmd_get_particle_energies");
         }},
        {"expression_lj", [&] { traverse("4 * (r^-12 - r^-6)"); }},
        {"expression_count", [&] { traverse("r < 1.5"); }},
    };
    const nlohmann::json info = engine_info(sim);
    std::vector<Row> rows;
    rows.push_back({n, info.at("backend").get<std::string>(), info.at("precision").get<std::string>(), "baseline",
                    baseline, 0.0});
    double builtin = 0;
    for (const Form& form : forms) {
        const double net = median_seconds_per_call(options, form.call) - baseline;
        if (std::string(form.name) == "builtin_energy_read") builtin = net;
        rows.push_back({n, rows[0].backend, rows[0].precision, form.name, net, 0.0});
    }
    for (Row& row : rows)
        if (row.form != "baseline" && builtin > 0) row.ratio = row.secondsPerCall / builtin;
    return rows;
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    CLI::App app{"A transverser against a built-in pair term over the LJ liquid, over the structmd C API"};
    app.add_option("--n", options.sizes, "Particle counts, rounded to 4 k^3 (repeatable)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--backend", options.backends, "auto, cpu or cuda (repeatable)")
        ->check(CLI::IsMember({"auto", "cpu", "cuda"}))
        ->capture_default_str();
    app.add_option("--precision", options.precisions, "single, mixed or double (repeatable)")
        ->check(CLI::IsMember({"single", "mixed", "double"}))
        ->capture_default_str();
    app.add_option("--calls", options.calls, "Calls per timed sample")->check(CLI::PositiveNumber)->capture_default_str();
    app.add_option("--repeats", options.repeats, "Timed samples (the median is reported)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--warmup", options.warmup, "Untimed calls of each form first (NVRTC compiles at the first)")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_option("--threads", options.threads, "CPU threads (default: all OpenMP offers)")->check(CLI::PositiveNumber);
    app.add_option("--csv", options.csvPath, "Also write the rows to this CSV file");
    CLI11_PARSE(app, argc, argv);

    std::ofstream csv;
    if (!options.csvPath.empty() &&
        !open_csv(csv, options.csvPath, "n,backend,precision,form,seconds_per_call,ratio_to_builtin"))
        return 2;
    std::printf("structmd %s, %d calls per sample x %d samples (median), net of the baseline\n", structmd_version(),
                options.calls, options.repeats);
    std::printf("%10s  %-7s  %-9s  %-16s  %14s  %8s\n", "N", "backend", "precision", "form", "us/call", "ratio");
    int failures = 0;
    for (const auto& backend : options.backends)
        for (const auto& precision : options.precisions)
            for (const int64_t size : options.sizes) {
                try {
                    for (const Row& row : measure(options, size, backend, precision)) {
                        std::printf("%10lld  %-7s  %-9s  %-16s  %14.2f  %8.3f\n", static_cast<long long>(row.particles),
                                    row.backend.c_str(), row.precision.c_str(), row.form.c_str(),
                                    1e6 * row.secondsPerCall, row.ratio);
                        if (csv.is_open())
                            csv << row.particles << ',' << row.backend << ',' << row.precision << ',' << row.form << ','
                                << row.secondsPerCall << ',' << row.ratio << '\n'
                                << std::flush;
                    }
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
