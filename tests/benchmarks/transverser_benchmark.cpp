// The cost of a transverser against a built-in pair term over the same liquid (issue 35: a user's
// traversal must run as fast as a built-in pair term over the same list, within 1.2x). The LJ
// liquid of lj_liquid.hpp (cut at 2.5 sigma), driven through the public C API:
//
//   structmd_transverser_benchmark [--n N]... [--backend B]... [--precision P]... [--calls C]
//                                  [--repeats R] [--warmup W] [--threads K] [--plugin PATH]...
//                                  [--csv PATH]
//
// Each form is timed as C calls of "structmd_step(sim, 1) + the form", so that every call sees new
// positions (no cached result is reused, and each list follows the particles as it does in a run:
// refreshed every step, rebuilt when some particle moved half its skin), the median of R such
// samples reported per call, less the median of C bare steps (the "baseline" row):
//   builtin_energy       structmd_compute(STRUCTMD_ENERGY): the LennardJonesType1 pair kernel for
//                        per-particle energies alone (the step made the forces); nothing leaves
//                        the engine
//   builtin_energy_read  the same, then structmd_get_particle_energies: n values to the host
//   expression_lj        structmd_traverse_expression("4 * (r^-12 - r^-6)", 2.5): the LJ energy as
//                        an expression transverser over its own list (skin 0.25 against the
//                        liquid's 0.3), compiled by NVRTC on CUDA, interpreted on the CPU; it
//                        copies its n sums to the host, as builtin_energy_read does
//   expression_count     structmd_traverse_expression("r < 1.5", 2.5): neighbour counts, same list
// and, for the example plugins loaded with --plugin (examples/plugins; CMake builds both beside
// this program), their transversers through structmd_traverse_view, the output left in the engine
// (on the GPU for CUDA) as builtin_energy's is:
//   plugin_count_view    NeighbourCount over a list of cutoff 2.5: one value per particle
//   plugin_lj_force_view LennardJonesForce (epsilon 1, sigma 1) over the same: the seeds' LJ
//                        Potential as a Transverser, three values per particle
// ratio: the form's net time over its built-in counterpart's: builtin_energy_read's for the forms
// that copy their values to the host, builtin_energy's for those that leave them in the engine. The
// CSV columns: n, backend, precision, form, seconds_per_call, ratio_to_builtin.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <dlpack/dlpack.h>
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
    std::vector<std::string> plugins;
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

// Whether a plugin the process loaded registered a transverser of this name.
bool has_transverser(structmd_sim* sim, const char* name) {
    int values = 0;
    return structmd_transverser_values(sim, name, &values) == STRUCTMD_OK;
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
    const auto traverse_view = [&](const char* name, const char* parameters) {
        step();
        structmd_dlpack_tensor* view = nullptr;
        check(structmd_traverse_view(sim, name, parameters, kCutOff, &view), sim, "structmd_traverse_view");
        view->deleter(view);
    };

    const double baseline = median_seconds_per_call(options, step);
    struct Form {
        std::string name;
        std::function<void()> call;
        std::string against;  // the built-in form of the ratio; none for the built-ins themselves
    };
    std::vector<Form> forms = {
        {"builtin_energy", energy, ""},
        {"builtin_energy_read",
         [&] {
             energy();
             check(structmd_get_particle_energies(sim, energies.data(), n), sim, "structmd_get_particle_energies");
         },
         ""},
        {"expression_lj", [&] { traverse("4 * (r^-12 - r^-6)"); }, "builtin_energy_read"},
        {"expression_count", [&] { traverse("r < 1.5"); }, "builtin_energy_read"},
    };
    if (has_transverser(sim, "NeighbourCount"))
        forms.push_back({"plugin_count_view", [&] { traverse_view("NeighbourCount", nullptr); }, "builtin_energy"});
    if (has_transverser(sim, "LennardJonesForce"))
        forms.push_back({"plugin_lj_force_view",
                         [&] { traverse_view("LennardJonesForce", R"({"epsilon": 1, "sigma": 1})"); },
                         "builtin_energy"});
    const nlohmann::json info = engine_info(sim);
    std::vector<Row> rows;
    rows.push_back({n, info.at("backend").get<std::string>(), info.at("precision").get<std::string>(), "baseline",
                    baseline, 0.0});
    std::map<std::string, double> net;
    for (const Form& form : forms) {
        net[form.name] = median_seconds_per_call(options, form.call) - baseline;
        const double builtin = form.against.empty() ? 0.0 : net.at(form.against);
        rows.push_back({n, rows[0].backend, rows[0].precision, form.name, net[form.name],
                        builtin > 0 ? net[form.name] / builtin : 0.0});
    }
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
    app.add_option("--plugin", options.plugins, "A plugin library to load: its transversers are timed too (repeatable)")
        ->check(CLI::ExistingFile);
    app.add_option("--csv", options.csvPath, "Also write the rows to this CSV file");
    CLI11_PARSE(app, argc, argv);

    for (const auto& plugin : options.plugins)
        if (structmd_load_plugin(plugin.c_str()) != STRUCTMD_OK) {
            std::fprintf(stderr, "%s\n", structmd_last_error(nullptr));
            return 2;
        }

    std::ofstream csv;
    if (!options.csvPath.empty() &&
        !open_csv(csv, options.csvPath, "n,backend,precision,form,seconds_per_call,ratio_to_builtin"))
        return 2;
    std::printf("structmd %s, %d calls per sample x %d samples (median), net of the baseline\n", structmd_version(),
                options.calls, options.repeats);
    std::printf("%10s  %-7s  %-9s  %-20s  %14s  %8s\n", "N", "backend", "precision", "form", "us/call", "ratio");
    int failures = 0;
    for (const auto& backend : options.backends)
        for (const auto& precision : options.precisions)
            for (const int64_t size : options.sizes) {
                try {
                    for (const Row& row : measure(options, size, backend, precision)) {
                        std::printf("%10lld  %-7s  %-9s  %-20s  %14.2f  %8.3f\n", static_cast<long long>(row.particles),
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
