// structmd: the command-line launcher. It drives the engine through the public C API only, as any
// host program would: create a handle, load the input, step along the schedule, report.
//
//   structmd run INPUT.json [--backend auto|cpu|cuda] [--precision single|mixed|double] [--threads N]
//                [--plugin LIBRARY.so]... [--quiet]
//   structmd --version
//
// Exit status: 0 on success, the structmd_status code (1..9) when the engine reports a failure,
// CLI11's own codes for a malformed command line.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <new>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "structmd.hpp"

namespace {

using structmd::host::check;
using structmd::host::Failure;
using structmd::host::Handle;

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

struct RunOptions {
    std::string input;
    std::string backend = "auto";
    std::string precision = "single";
    int threads = 0;  // 0: the engine's default (all threads OpenMP offers)
    std::vector<std::string> plugins;  // the handle's "plugins" option
    bool quiet = false;
};

// The fields of structmd_get_info the launcher reports.
struct EngineInfo {
    std::string backend;
    std::string precision;
    std::string device;
    int64_t threads = 0;
    int64_t particles = 0;
    int64_t final_step = -1;
};

EngineInfo read_info(const structmd_sim* sim) {
    const auto info = nlohmann::json::parse(structmd::host::info(sim));
    EngineInfo out;
    out.backend = info.at("backend").get<std::string>();
    out.precision = info.at("precision").get<std::string>();
    out.device = info.value("device", std::string());
    out.threads = info.value("threads", int64_t{0});
    out.particles = info.at("particles").get<int64_t>();
    out.final_step = info.at("final_step").get<int64_t>();
    return out;
}

int64_t current_step(const structmd_sim* sim) {
    int64_t step = 0;
    check(structmd_get_step(sim, &step), sim, "structmd_get_step");
    return step;
}

// Picks how many steps the next structmd_step call takes so that one call lasts about
// target_seconds: short enough for a lively progress line, long enough that the per-call cost
// (a device synchronisation, a host round trip) is negligible. Growth is capped per call because
// the first steps (first neighbour-list build, warm caches) say little about the steady speed.
class ChunkPlanner {
public:
    explicit ChunkPlanner(double target_seconds) : target_seconds_(target_seconds) {}

    int64_t next() const { return chunk_; }

    void record(int64_t steps, double seconds) {
        const int64_t grown = steps * kMaxGrowth;
        if (seconds <= 0.0) {
            chunk_ = grown;
            return;
        }
        const double wanted = static_cast<double>(steps) * target_seconds_ / seconds;
        chunk_ = std::clamp<int64_t>(static_cast<int64_t>(wanted), 1, grown);
    }

private:
    static constexpr int64_t kMaxGrowth = 4;
    double target_seconds_;
    int64_t chunk_ = 1;
};

std::string format_duration(double seconds) {
    const auto total = static_cast<int64_t>(seconds + 0.5);
    char text[32];
    std::snprintf(text, sizeof text, "%lld:%02lld:%02lld", static_cast<long long>(total / 3600),
                  static_cast<long long>(total / 60 % 60), static_cast<long long>(total % 60));
    return text;
}

// One status line on a terminal, rewritten in place with '\r'; redraws are throttled so the
// terminal never costs more than a few writes per second.
class ProgressLine {
public:
    ProgressLine(FILE* stream, int64_t first_step, int64_t final_step)
        : stream_(stream), first_step_(first_step), final_step_(final_step) {}
    // Moves past the line, also when a failure ends the run early, so later output starts clean.
    ~ProgressLine() {
        if (drawn_length_ > 0) std::fputc('\n', stream_);
        std::fflush(stream_);
    }
    ProgressLine(const ProgressLine&) = delete;
    ProgressLine& operator=(const ProgressLine&) = delete;

    void update(int64_t step, double elapsed, bool force) {
        if (!force && elapsed - last_draw_ < kMinInterval) return;
        last_draw_ = elapsed;

        const double done = static_cast<double>(step - first_step_);
        const double total = static_cast<double>(final_step_ - first_step_);
        const double rate = elapsed > 0.0 ? done / elapsed : 0.0;
        const double percent = total > 0.0 ? 100.0 * done / total : 100.0;
        const std::string eta =
            rate > 0.0 ? format_duration((total - done) / rate) : std::string("--:--:--");

        char line[160];
        const int length = std::snprintf(line, sizeof line,
                                          "%5.1f%%  step %lld/%lld  %.4g steps/s  ETA %s", percent,
                                          static_cast<long long>(step),
                                          static_cast<long long>(final_step_), rate, eta.c_str());
        // Pad over the previous, possibly longer, line, and leave the cursor at the line's start so
        // that a log line the engine writes meanwhile replaces the progress line instead of
        // trailing after it.
        std::fprintf(stream_, "\r%s%*s\r", line, std::max(0, drawn_length_ - length), "");
        std::fflush(stream_);
        drawn_length_ = length;
    }

private:
    static constexpr double kMinInterval = 0.25;  // seconds between redraws
    FILE* stream_;
    int64_t first_step_;
    int64_t final_step_;
    double last_draw_ = -1.0;
    int drawn_length_ = 0;
};

std::string create_options(const RunOptions& options) {
    nlohmann::json json = {{"backend", options.backend},
                           {"precision", options.precision},
                           {"log", options.quiet ? "warning" : "info"}};
    if (options.threads > 0) json["threads"] = options.threads;
    if (!options.plugins.empty()) json["plugins"] = options.plugins;
    return json.dump();
}

// Steps until the schedule ends. With a progress line, steps go in chunks of about half a second;
// without one, a single structmd_run call does it all.
void run_schedule(structmd_sim* sim, int64_t first_step, int64_t final_step, bool show_progress) {
    if (!show_progress || final_step < 0) {
        check(structmd_run(sim), sim, "structmd_run");
        return;
    }
    ProgressLine progress(stderr, first_step, final_step);
    ChunkPlanner planner(0.5);
    const auto start = Clock::now();
    int64_t step = first_step;
    progress.update(step, 0.0, true);
    while (step < final_step) {
        const int64_t chunk = std::min(planner.next(), final_step - step);
        const auto chunk_start = Clock::now();
        check(structmd_step(sim, chunk), sim, "structmd_step");
        planner.record(chunk, seconds_since(chunk_start));
        step = current_step(sim);
        progress.update(step, seconds_since(start), step >= final_step);
    }
}

void print_summary(const RunOptions& options, const EngineInfo& info, int64_t steps, double wall) {
    const double rate = wall > 0.0 ? static_cast<double>(steps) / wall : 0.0;
    std::string backend = info.backend;
    if (info.backend == "cuda" && !info.device.empty()) backend += " (" + info.device + ")";
    if (info.backend == "cpu" && info.threads > 0) backend += " (" + std::to_string(info.threads) + " threads)";

    std::printf("structmd run: %s\n", options.input.c_str());
    std::printf("  steps             %lld\n", static_cast<long long>(steps));
    std::printf("  particles         %lld\n", static_cast<long long>(info.particles));
    std::printf("  wall time         %.3f s\n", wall);
    std::printf("  steps/s           %.4g\n", rate);
    std::printf("  particle-steps/s  %.4g\n", rate * static_cast<double>(info.particles));
    std::printf("  backend           %s\n", backend.c_str());
    std::printf("  precision         %s\n", info.precision.c_str());
}

int run_command(const RunOptions& options) {
    try {
        Handle simulation(create_options(options));
        structmd_sim* sim = simulation.get();
        check(structmd_load_file(sim, options.input.c_str()), sim, "structmd_load_file");

        const EngineInfo info = read_info(sim);
        const int64_t first_step = current_step(sim);
        const bool show_progress = !options.quiet && isatty(STDERR_FILENO);

        const auto start = Clock::now();
        run_schedule(sim, first_step, info.final_step, show_progress);
        const double wall = seconds_since(start);

        if (!options.quiet) print_summary(options, info, current_step(sim) - first_step, wall);
        return 0;
    } catch (const Failure& failure) {
        std::fflush(stdout);
        std::fprintf(stderr, "structmd: %s (status %d)\n", failure.what(), static_cast<int>(failure.status()));
        return failure.status();
    } catch (const nlohmann::json::exception& error) {
        std::fprintf(stderr, "structmd: unexpected structmd_get_info output: %s\n", error.what());
        return STRUCTMD_ERR_INTERNAL;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "structmd: out of host memory\n");
        return STRUCTMD_ERR_MEMORY;
    }
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"structmd: molecular dynamics from a UAMMD-structured JSON input"};
    app.set_version_flag("--version", std::string(structmd_version()));
    app.require_subcommand(1);

    RunOptions options;
    CLI::App* run = app.add_subcommand("run", "Run a simulation until its integrator schedule ends");
    run->add_option("input", options.input, "Input document (UAMMD-structured JSON)")
        ->required()
        ->check(CLI::ExistingFile);
    run->add_option("--backend", options.backend, "Where to run: auto picks CUDA when a GPU is usable")
        ->check(CLI::IsMember({"auto", "cpu", "cuda"}))
        ->capture_default_str();
    run->add_option("--precision", options.precision, "Floating-point precision of the engine")
        ->check(CLI::IsMember({"single", "mixed", "double"}))
        ->capture_default_str();
    run->add_option("--threads", options.threads, "CPU threads (default: all OpenMP offers)")
        ->check(CLI::PositiveNumber);
    run->add_option("--plugin", options.plugins,
                    "A plugin library whose components the input may use (docs/plugins.md); repeatable");
    run->add_flag("--quiet", options.quiet,
                  "No progress line, no summary, engine log at warning level (errors still print)");

    CLI11_PARSE(app, argc, argv);
    return run_command(options);
}
