// structmd: the command-line launcher. It drives the engine through the public C API only, as any
// host program would: create a handle, load the input, step along the schedule, report.
//
//   structmd run INPUT.json [--backend auto|cpu|cuda] [--precision single|mixed|double] [--threads N]
//                [--plugin LIBRARY.so]... [--steps N] [--thermo K] [--progress SECONDS] [--quiet] [--mpi]
//   mpirun -np K structmd run INPUT.json ...   (the input's batches spread over K ranks)
//   structmd client --ipi HOST:PORT|unix:NAME INPUT.json [--backend ...] [--precision ...] [--threads N]
//                   [--plugin LIBRARY.so]... [--length-unit A] [--energy-unit EV] [--connect-timeout S]
//                   [--read-timeout S] [--quiet]
//   structmd --version
//
// Progress goes to standard error: a line redrawn in place on a terminal, one line every
// --progress seconds (default 10) otherwise, as in a batch job's log. --thermo K prints the energies,
// temperature and pressure every K steps on standard output. A run stops at the first failure (a
// blow-up included) with the engine's message and a hint.
//
// Under MPI (mpirun, or --mpi) every rank runs the same calls on its share of the batches, and rank 0
// alone prints: progress, thermo rows, the summary and failures.
//
// Exit status: 0 on success, the structmd_status code (1..10) when the engine reports a failure
// (5, STRUCTMD_ERR_IO, for an input file that cannot be read: missing, a directory, unreadable),
// CLI11's own codes for a malformed command line.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <new>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "ipi_client.hpp"
#include "mpi_session.hpp"
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
    bool noStepGraphs = false;         // the handle's "step_graphs": false
    int64_t steps = -1;                // -1: until the schedule ends
    int64_t thermo = 0;                // 0: no energies on screen
    double progressSeconds = 10.0;     // between progress lines without a terminal
    bool quiet = false;
    bool mpi = false;                  // --mpi: MPI without an MPI launcher's environment
    const structmd::launcher::MpiSession* session = nullptr;  // the MPI session, when there is one
    bool prints() const { return !session || session->rank() == 0; }
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

// The simulationStep entry that ended the last step call early, or empty.
std::string stopped_by(const structmd_sim* sim) {
    const auto info = nlohmann::json::parse(structmd::host::info(sim));
    const auto it = info.find("stopped_by");
    return it != info.end() && it->is_string() ? it->get<std::string>() : std::string();
}

int64_t current_step(const structmd_sim* sim) {
    int64_t step = 0;
    check(structmd_get_step(sim, &step), sim, "structmd_get_step");
    return step;
}

// The input with its integrator schedule cut to `steps` steps (rows in order, each shortened to what
// is left), or with the last row that runs extended when the schedule is shorter: the engine then
// ends the schedule at the step --steps asks for, and gives the outputs their final state there as
// it does at any schedule's end. Empty when the file cannot be read, is not JSON, gives a key twice
// (which rewriting would hide from the engine) or has no schedule table: structmd_load_file then
// reads it as it is, and names what is wrong.
std::optional<std::string> input_cut_to(const std::string& path, int64_t steps) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) return std::nullopt;  // a device may never end
    std::ifstream file(path, std::ios::binary);
    if (!file) return std::nullopt;
    std::ostringstream text;
    text << file.rdbuf();
    std::vector<std::set<std::string>> keysOfOpenObjects;
    bool repeatedKey = false;
    const auto noticeRepeatedKeys = [&](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
        using Event = nlohmann::json::parse_event_t;
        if (event == Event::object_start) keysOfOpenObjects.emplace_back();
        if (event == Event::object_end) keysOfOpenObjects.pop_back();
        if (event == Event::key && !keysOfOpenObjects.back().insert(parsed.get<std::string>()).second)
            repeatedKey = true;
        return true;
    };
    try {
        auto document = nlohmann::json::parse(text.str(), noticeRepeatedKeys, true, /*ignore_comments=*/true);
        if (repeatedKey) return std::nullopt;
        const nlohmann::json schedule_type = {"Schedule", "Integrator"};
        for (auto& entry : document.at("integrator")) {
            if (!entry.is_object() || entry.value("type", nlohmann::json()) != schedule_type) continue;
            const auto& labels = entry.at("labels");
            const auto column = [&](const char* label) {
                const auto at = std::find(labels.begin(), labels.end(), label);
                if (at == labels.end()) throw std::out_of_range(label);
                return static_cast<size_t>(at - labels.begin());
            };
            const size_t order = column("order"), length = column("steps");
            auto& rows = entry.at("data");
            std::vector<nlohmann::json*> ordered;
            for (auto& row : rows) ordered.push_back(&row);
            std::stable_sort(ordered.begin(), ordered.end(), [&](const nlohmann::json* a, const nlohmann::json* b) {
                return a->at(order).get<int64_t>() < b->at(order).get<int64_t>();
            });
            int64_t left = steps;
            nlohmann::json* lastRunning = ordered.empty() ? nullptr : ordered.back();
            for (nlohmann::json* row : ordered) {
                const int64_t given = row->at(length).get<int64_t>();
                if (given > 0) lastRunning = row;
                const int64_t kept = std::clamp<int64_t>(given, 0, left);
                (*row)[length] = kept;
                left -= kept;
            }
            if (!lastRunning) return std::nullopt;
            (*lastRunning)[length] = (*lastRunning)[length].get<int64_t>() + left;
            return document.dump();
        }
    } catch (const std::exception&) {
    }
    return std::nullopt;
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
// Without a terminal (a batch job's log), each update that is due is a line of its own instead.
class ProgressLine {
public:
    ProgressLine(FILE* stream, int64_t first_step, int64_t final_step, bool terminal, double interval)
        : stream_(stream), first_step_(first_step), final_step_(final_step), terminal_(terminal),
          interval_(terminal ? kMinInterval : interval) {}
    // Moves past the line, also when a failure ends the run early, so later output starts clean.
    ~ProgressLine() {
        if (drawn_length_ > 0) std::fputc('\n', stream_);
        std::fflush(stream_);
    }
    ProgressLine(const ProgressLine&) = delete;
    ProgressLine& operator=(const ProgressLine&) = delete;

    void update(int64_t step, double elapsed, bool force) {
        if (!force && elapsed - last_draw_ < interval_) return;
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
        if (!terminal_) {
            std::fprintf(stream_, "structmd: %s\n", line);
            std::fflush(stream_);
            return;
        }
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
    bool terminal_;
    double interval_;
    double last_draw_ = -1.0;
    int drawn_length_ = 0;
};

std::string create_options(const RunOptions& options) {
    nlohmann::json json = {{"backend", options.backend},
                           {"precision", options.precision},
                           {"log", options.quiet || !options.prints() ? "warning" : "info"}};
    if (options.threads > 0) json["threads"] = options.threads;
    if (!options.plugins.empty()) json["plugins"] = options.plugins;
    if (options.noStepGraphs) json["step_graphs"] = false;
    if (options.session) json["mpi_comm"] = options.session->world_handle();
    return json.dump();
}

double energy(structmd_sim* sim, const char* term) {
    double value = 0.0;
    check(structmd_get_energy(sim, term, &value), sim, "structmd_get_energy");
    return value;
}

// The energies, temperature and pressure on standard output, a header first, one row per call.
class ThermoTable {
public:
    explicit ThermoTable(bool prints) : prints_(prints) {}

    // Every rank asks for the energies (a collective call under MPI); rank 0 prints them.
    void print(structmd_sim* sim, int64_t step) {
        const double kinetic = energy(sim, "kinetic"), potential = energy(sim, "potential");
        const double total = energy(sim, "total");
        double temperature = 0.0, pressure = 0.0;
        check(structmd_get_temperature(sim, &temperature), sim, "structmd_get_temperature");
        check(structmd_get_pressure(sim, &pressure), sim, "structmd_get_pressure");
        if (!prints_) return;
        if (!headed_) {
            std::printf("%12s  %16s  %16s  %16s  %16s  %16s\n", "step", "kinetic", "potential", "total",
                        "temperature", "pressure");
            headed_ = true;
        }
        std::printf("%12lld  %16.8g  %16.8g  %16.8g  %16.8g  %16.8g\n", static_cast<long long>(step), kinetic,
                    potential, total, temperature, pressure);
        std::fflush(stdout);
    }

private:
    bool prints_;
    bool headed_ = false;
};

// Steps from first_step to final_step in chunks of about half a second (shorter where a thermo row
// is due), with progress and thermo rows between chunks. A failing step ends the run there, and so
// does a flow-control step of the input that asks to stop.
void run_steps(structmd_sim* sim, const RunOptions& options, int64_t first_step, int64_t final_step) {
    std::optional<ProgressLine> progress;
    if (!options.quiet && options.prints())
        progress.emplace(stderr, first_step, final_step, isatty(STDERR_FILENO) != 0, options.progressSeconds);
    ThermoTable thermo(options.prints());
    ChunkPlanner planner(0.5);
    const auto start = Clock::now();
    int64_t step = first_step;
    if (options.thermo > 0) thermo.print(sim, step);
    while (step < final_step) {
        // Under MPI every rank takes rank 0's chunk: each structmd_step call is collective.
        int64_t chunk = std::min(options.session ? options.session->rank0_value(planner.next()) : planner.next(),
                                 final_step - step);
        if (options.thermo > 0) chunk = std::min(chunk, options.thermo - step % options.thermo);
        const auto chunk_start = Clock::now();
        check(structmd_step(sim, chunk), sim, "structmd_step");
        planner.record(chunk, seconds_since(chunk_start));
        step = current_step(sim);
        if (options.thermo > 0 && (step % options.thermo == 0 || step >= final_step)) thermo.print(sim, step);
        const std::string stopper = stopped_by(sim);
        if (progress) progress->update(step, seconds_since(start), step >= final_step || !stopper.empty());
        if (!stopper.empty()) {
            progress.reset();  // ends its line first
            if (!options.quiet && options.prints())
                std::fprintf(stderr, "structmd run: stopped at step %lld by simulationStep.%s\n",
                             static_cast<long long>(step), stopper.c_str());
            return;
        }
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
    if (options.session) std::printf("  MPI ranks         %d\n", options.session->size());
}

int run_command(const RunOptions& options) {
    try {
        Handle simulation(create_options(options));
        structmd_sim* sim = simulation.get();
        const std::optional<std::string> cut = options.steps >= 0 ? input_cut_to(options.input, options.steps)
                                                                  : std::nullopt;
        if (cut)
            check(structmd_load_string(sim, cut->c_str()), sim, "structmd_load_string");
        else
            check(structmd_load_file(sim, options.input.c_str()), sim, "structmd_load_file");

        const EngineInfo info = read_info(sim);
        const int64_t first_step = current_step(sim);
        const int64_t final_step = options.steps >= 0 ? first_step + options.steps : info.final_step;

        const auto start = Clock::now();
        if (final_step < 0 || (options.steps < 0 && options.thermo == 0 && options.quiet))
            check(structmd_run(sim), sim, "structmd_run");
        else
            run_steps(sim, options, first_step, final_step);
        const double wall = seconds_since(start);

        if (!options.quiet && options.prints()) print_summary(options, info, current_step(sim) - first_step, wall);
        return 0;
    } catch (const Failure& failure) {
        std::fflush(stdout);
        // Every rank fails alike (the engine agrees on failures over the ranks); rank 0 says why.
        if (!options.prints()) return failure.status();
        std::fprintf(stderr, "structmd: stopped: %s (status %d)\n", failure.what(), static_cast<int>(failure.status()));
        if (failure.status() == STRUCTMD_ERR_NUMERICAL)
            std::fprintf(stderr,
                         "structmd: the system blew up; the state before the failing steps was kept. Try a smaller "
                         "timeStep, a minimisation first, or look for overlapping particles in the input.\n");
        if (failure.status() == STRUCTMD_ERR_IO && failure.call() == "structmd_load_file")
            std::fprintf(stderr, "structmd: cannot read the input file %s\n", options.input.c_str());
        if (failure.status() == STRUCTMD_ERR_INPUT)
            std::fprintf(stderr, "structmd: the input was not accepted; the message names the JSON path to fix.\n");
        return failure.status();
    } catch (const nlohmann::json::exception& error) {
        std::fprintf(stderr, "structmd: unexpected structmd_get_info output: %s\n", error.what());
        return STRUCTMD_ERR_INTERNAL;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "structmd: out of host memory\n");
        return STRUCTMD_ERR_MEMORY;
    }
}

// The options of structmd_create that every subcommand takes.
void add_engine_options(CLI::App* command, RunOptions& options) {
    command->add_option("--backend", options.backend, "Where to run: auto picks CUDA when a GPU is usable")
        ->check(CLI::IsMember({"auto", "cpu", "cuda"}))
        ->capture_default_str();
    command->add_option("--precision", options.precision, "Floating-point precision of the engine")
        ->check(CLI::IsMember({"single", "mixed", "double"}))
        ->capture_default_str();
    command->add_option("--threads", options.threads, "CPU threads (default: all OpenMP offers)")
        ->check(CLI::PositiveNumber);
    command->add_option("--plugin", options.plugins,
                        "A plugin library whose components the input may use (docs/plugins.md); repeatable");
    command->add_flag("--no-step-graphs", options.noStepGraphs,
                      "Launch each GPU kernel as it comes, not as CUDA graphs: slower, for profilers");
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"structmd: molecular dynamics from a UAMMD-structured JSON input"};
    app.set_version_flag("--version", std::string(structmd_version()));
    app.require_subcommand(1);

    RunOptions options;
    CLI::App* run = app.add_subcommand("run", "Run a simulation until its integrator schedule ends (or --steps)");
    // No CLI::ExistingFile check: the engine reads the input and says why it cannot, with the
    // documented status 5 as exit code rather than CLI11's 105.
    run->add_option("input", options.input, "Input document (UAMMD-structured JSON)")->required();
    add_engine_options(run, options);
    run->add_option("--steps", options.steps,
                    "Steps to run instead of the schedule's (cut there, or its last integrator goes on); "
                    "the outputs write their final state at that step")
        ->check(CLI::NonNegativeNumber);
    run->add_option("--thermo", options.thermo,
                    "Print kinetic, potential and total energy, temperature and pressure every K steps")
        ->check(CLI::PositiveNumber);
    run->add_option("--progress", options.progressSeconds,
                    "Seconds between progress lines when standard error is not a terminal")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    run->add_flag("--quiet", options.quiet,
                  "No progress line, no summary, engine log at warning level (errors still print)");
    run->add_flag("--mpi", options.mpi,
                  "Spread the input's batches over MPI ranks (implied under mpirun, srun or another MPI launcher)");

    // The engine as an i-PI client: the same engine options as run, double precision by default since
    // the server's optimiser or integrator expects it.
    RunOptions clientEngine;
    clientEngine.precision = "double";
    structmd::launcher::IpiClientOptions clientOptions;
    CLI::App* client =
        app.add_subcommand("client", "Answer the force requests of an i-PI server (i-PI, ASE's SocketIOCalculator)");
    client
        ->add_option("--ipi", clientOptions.address,
                     "The server: HOST:PORT, or unix:NAME for the UNIX socket /tmp/ipi_NAME")
        ->required();
    client
        ->add_option("input", clientOptions.input,
                     "Input document (UAMMD-structured JSON) whose particles are the server's atoms")
        ->required();
    add_engine_options(client, clientEngine);
    client->add_option("--length-unit", clientOptions.lengthUnit, "One input length in Å (the server speaks bohr)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    client->add_option("--energy-unit", clientOptions.energyUnit, "One input energy in eV (the server speaks hartree)")
        ->check(CLI::PositiveNumber)
        ->capture_default_str();
    client
        ->add_option("--connect-timeout", clientOptions.connectTimeout,
                     "Seconds to keep trying while no server listens")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    client
        ->add_option("--read-timeout", clientOptions.readTimeout,
                     "Seconds to wait for each message from the server before giving up (0: forever)")
        ->check(CLI::NonNegativeNumber)
        ->capture_default_str();
    client->add_flag("--quiet", clientEngine.quiet, "No connection messages, engine log at warning level");

    CLI11_PARSE(app, argc, argv);
    if (client->parsed()) {
        clientOptions.createOptions = create_options(clientEngine);
        clientOptions.quiet = clientEngine.quiet;
        return structmd::launcher::run_ipi_client(clientOptions);
    }
    if (!structmd::launcher::MpiSession::requested(options.mpi)) return run_command(options);
    if (!structmd::launcher::MpiSession::compiled()) {
        std::fprintf(stderr, "structmd: MPI is not compiled in: this structmd was built without MPI (install MPI, "
                             "e.g. Debian's libopenmpi-dev, and build again; CMake option STRUCTMD_MPI)\n");
        return STRUCTMD_ERR_UNSUPPORTED;
    }
    structmd::launcher::MpiSession session(&argc, &argv);
    options.session = &session;
    return run_command(options);
}
