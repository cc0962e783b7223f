// Cost of a coupling loop over the public C API: what a host that exchanges a region of the system
// every step (a continuum solver, a QM region, an ML model) pays on top of the step itself. The
// system is the LJ liquid of lj_liquid.hpp.
//
//   structmd_coupling_benchmark [--n N]... [--backend B]... [--precision P]... [--fraction F]
//                               [--seconds T] [--repeats R] [--warmup W] [--threads K] [--csv PATH]
//
// For every (backend, precision, N) the program loads a fresh system, takes W untimed steps, and
// times two loops of the same number of iterations, alternating R times:
//   step:     structmd_step(sim, 1)
//   exchange: structmd_step(sim, 1); structmd_get_positions_of(region); structmd_set_external_forces_of(region)
// where the region is F x N particles (default 1%), spread evenly over the ids. The forces the host
// sets are a weak pull towards the box centre (1e-3 per unit of distance), small beside the liquid's
// own, so both loops run the same dynamics. The iterations per loop are chosen so one step loop takes
// about T seconds. Reported: microseconds per iteration of each loop (medians), the exchange's extra
// cost in microseconds and as a fraction of the step, the time spent inside each of the two calls
// (medians of their means over the exchange loop: the get includes waiting for the step's kernels to
// finish, the set only queues its work), and the bytes the exchange moves between host and backend per
// iteration beyond those of the step itself (structmd_get_counters), which scale with the region,
// not with N.
//
// CSV columns: n, backend, precision, region, iterations, step_us, exchange_us, extra_us,
// extra_fraction, bytes_per_exchange, get_us, set_us.
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

constexpr int64_t kUnendingSchedule = 1'000'000'000'000;
constexpr double kPull = 1e-3;  // the host's force per unit of distance from the box centre

struct Options {
    std::vector<int64_t> sizes{10976};
    std::vector<std::string> backends{"auto"};
    std::vector<std::string> precisions{"single"};
    double fraction = 0.01;
    double seconds = 0.5;
    int repeats = 3;
    int64_t warmup = 100;
    int threads = 0;
    std::string csvPath;
};

struct Row {
    int64_t particles = 0;
    std::string backend;
    std::string precision;
    int64_t region = 0;
    int64_t iterations = 0;
    double stepMicroseconds = 0;
    double exchangeMicroseconds = 0;
    double bytesPerExchange = 0;
    double getMicroseconds = 0;  // inside structmd_get_positions_of, per call
    double setMicroseconds = 0;  // inside structmd_set_external_forces_of, per call
};

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double transferred_bytes(structmd_sim* sim) {
    const nlohmann::json c = engine_counters(sim);
    return c.at("host_to_device_bytes").get<double>() + c.at("device_to_host_bytes").get<double>();
}

class Exchange {
public:
    Exchange(structmd_sim* sim, int64_t particles, int64_t region) : sim_(sim), ids_(region), xyz_(3 * region), f_(3 * region) {
        for (int64_t k = 0; k < region; ++k) ids_[k] = k * particles / region;
    }
    void operator()() {
        const auto m = static_cast<int64_t>(ids_.size());
        const auto start = std::chrono::steady_clock::now();
        check(structmd_get_positions_of(sim_, ids_.data(), m, xyz_.data()), sim_, "structmd_get_positions_of");
        getSeconds += seconds_since(start);
        for (int64_t k = 0; k < 3 * m; ++k) f_[k] = -kPull * xyz_[k];  // wrapped positions: the centre is 0
        const auto set = std::chrono::steady_clock::now();
        check(structmd_set_external_forces_of(sim_, ids_.data(), m, f_.data()), sim_, "structmd_set_external_forces_of");
        setSeconds += seconds_since(set);
    }
    // Time spent inside each call since the last reset.
    double getSeconds = 0, setSeconds = 0;

private:
    structmd_sim* sim_;
    std::vector<int64_t> ids_;
    std::vector<double> xyz_, f_;
};

// Seconds for `iterations` of step(1), with the exchange after each step when `exchange` is given.
double timed_loop(structmd_sim* sim, int64_t iterations, Exchange* exchange) {
    const auto start = std::chrono::steady_clock::now();
    for (int64_t k = 0; k < iterations; ++k) {
        check(structmd_step(sim, 1), sim, "structmd_step");
        if (exchange) (*exchange)();
    }
    return seconds_since(start);
}

Row measure(const Options& options, int64_t requested, const std::string& backend, const std::string& precision) {
    Handle simulation(create_options(backend, precision, options.threads));
    structmd_sim* sim = simulation.get();
    {
        LjLiquid liquid;
        liquid.cells = cells_per_edge(requested);
        liquid.scheduleSteps = kUnendingSchedule;
        const std::string input = lj_liquid_input(liquid);
        check(structmd_load_string(sim, input.c_str()), sim, "structmd_load_string");
    }
    Row row;
    const nlohmann::json info = engine_info(sim);
    row.particles = info.at("particles").get<int64_t>();
    row.backend = info.at("backend").get<std::string>();
    row.precision = info.at("precision").get<std::string>();
    row.region = std::max<int64_t>(1, std::llround(options.fraction * static_cast<double>(row.particles)));
    Exchange exchange(sim, row.particles, row.region);
    exchange();  // the first call creates the external-force field: not part of the steady cost
    check(structmd_step(sim, options.warmup), sim, "structmd_step (warm-up)");

    int64_t iterations = 1;
    while (timed_loop(sim, iterations, nullptr) < 0.1 * options.seconds) iterations *= 2;
    iterations = std::max<int64_t>(1, std::llround(options.seconds / (timed_loop(sim, iterations, nullptr) / iterations)));
    row.iterations = iterations;

    std::vector<double> step, coupled, get, set;
    double bytes = 0;
    for (int repeat = 0; repeat < options.repeats; ++repeat) {
        const double start = transferred_bytes(sim);
        step.push_back(timed_loop(sim, iterations, nullptr) / iterations);
        const double between = transferred_bytes(sim);
        exchange.getSeconds = exchange.setSeconds = 0;
        coupled.push_back(timed_loop(sim, iterations, &exchange) / iterations);
        get.push_back(exchange.getSeconds / iterations);
        set.push_back(exchange.setSeconds / iterations);
        // What the exchange adds to a step's own transfers (the fault flag each call reads back).
        bytes = ((transferred_bytes(sim) - between) - (between - start)) / iterations;
    }
    row.stepMicroseconds = 1e6 * median(step);
    row.exchangeMicroseconds = 1e6 * median(coupled);
    row.bytesPerExchange = bytes;
    row.getMicroseconds = 1e6 * median(get);
    row.setMicroseconds = 1e6 * median(set);
    return row;
}

void print_row(const Row& r) {
    const double extra = r.exchangeMicroseconds - r.stepMicroseconds;
    std::printf("%10lld  %-7s  %-9s  %8lld  %10lld  %10.2f  %12.2f  %10.2f  %8.3f  %12.0f  %8.2f  %8.2f\n",
                static_cast<long long>(r.particles), r.backend.c_str(), r.precision.c_str(),
                static_cast<long long>(r.region), static_cast<long long>(r.iterations), r.stepMicroseconds,
                r.exchangeMicroseconds, extra, extra / r.stepMicroseconds, r.bytesPerExchange, r.getMicroseconds,
                r.setMicroseconds);
}

void write_csv_row(std::ofstream& csv, const Row& r) {
    const double extra = r.exchangeMicroseconds - r.stepMicroseconds;
    char line[512];
    std::snprintf(line, sizeof line, "%lld,%s,%s,%lld,%lld,%.4f,%.4f,%.4f,%.5f,%.0f,%.4f,%.4f\n",
                  static_cast<long long>(r.particles), r.backend.c_str(), r.precision.c_str(),
                  static_cast<long long>(r.region), static_cast<long long>(r.iterations), r.stepMicroseconds,
                  r.exchangeMicroseconds, extra, extra / r.stepMicroseconds, r.bytesPerExchange, r.getMicroseconds,
                  r.setMicroseconds);
    csv << line << std::flush;
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    CLI::App app{"Cost of exchanging a region of the system with the host every step, over the structmd C API"};
    app.add_option("--n", options.sizes, "Particle counts, rounded to 4 k^3 (repeatable)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--backend", options.backends, "auto, cpu or cuda (repeatable)")
        ->check(CLI::IsMember({"auto", "cpu", "cuda"}))
        ->capture_default_str();
    app.add_option("--precision", options.precisions, "single, mixed or double (repeatable)")
        ->check(CLI::IsMember({"single", "mixed", "double"}))
        ->capture_default_str();
    app.add_option("--fraction", options.fraction, "Share of the particles exchanged each step")
        ->check(CLI::Range(1e-9, 1.0))
        ->capture_default_str();
    app.add_option("--seconds", options.seconds, "Wall time of one timed loop of plain steps")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--repeats", options.repeats, "Timed pairs of loops (medians are reported)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    app.add_option("--warmup", options.warmup, "Untimed steps before timing")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    app.add_option("--threads", options.threads, "CPU threads (default: all OpenMP offers)")->check(CLI::PositiveNumber);
    app.add_option("--csv", options.csvPath, "Also write the rows to this CSV file");
    CLI11_PARSE(app, argc, argv);

    std::ofstream csv;
    if (!options.csvPath.empty() &&
        !open_csv(csv, options.csvPath,
                  "n,backend,precision,region,iterations,step_us,exchange_us,extra_us,extra_fraction,"
                  "bytes_per_exchange,get_us,set_us"))
        return 2;
    std::printf("structmd %s, LJ liquid, step(1) alone against step(1) + positions of a region + its external "
                "forces (%.3g%% of the particles), medians of %d\n",
                structmd_version(), 100 * options.fraction, options.repeats);
    std::printf("%10s  %-7s  %-9s  %8s  %10s  %10s  %12s  %10s  %8s  %12s  %8s  %8s\n", "N", "backend", "precision",
                "region", "iterations", "step us", "exchange us", "extra us", "extra/st", "bytes/iter", "get us",
                "set us");
    std::fflush(stdout);
    int failures = 0;
    for (const auto& backend : options.backends)
        for (const auto& precision : options.precisions)
            for (const int64_t size : options.sizes) {
                try {
                    const Row row = measure(options, size, backend, precision);
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
