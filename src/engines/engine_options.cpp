#include "engines/engine_options.hpp"

#include <limits>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "engines/devices.hpp"

namespace structmd {

std::string device_description(const EngineOptions& options) {
    return options.backend == BackendKind::cuda ? gpu_name(options.device) : "host CPU";
}

int cpu_thread_count(const EngineOptions& options) {
    return options.threads > 0 ? options.threads : cpu_default_threads();
}

namespace {

Error option_error(const std::string& key, const std::string& what) {
    return Error(STRUCTMD_ERR_ARGUMENT, "option \"" + key + "\": " + what);
}

// The value as a message shows it: a number, string, boolean or null as written; an array or an
// object by its kind alone, since writing out one nested by the caller a hundred thousand deep would
// recurse that deep.
std::string shown(const nlohmann::json& value) {
    if (value.is_array()) return "an array";
    if (value.is_object()) return "an object";
    return value.dump();
}

std::string string_option(const nlohmann::json& value, const std::string& key) {
    if (!value.is_string()) throw option_error(key, "expected a string, got " + shown(value));
    return value.get<std::string>();
}

std::string compiled_precision_names() {
    std::string names;
    for (const std::string& name : compiled_precisions()) names += (names.empty() ? "" : ", ") + name;
    return names;
}

// An int: a value beyond the int's range is refused, not wrapped (4294967297 threads was 1).
int int_option(const nlohmann::json& value, const std::string& key, int minimum) {
    const int largest = std::numeric_limits<int>::max();
    const bool fits = value.is_number_unsigned() ? value.get<unsigned long long>() <= static_cast<unsigned long long>(largest)
                                                 : value.is_number_integer() && value.get<long long>() <= largest;
    if (!fits || value.get<long long>() < minimum)
        throw option_error(key, "expected an integer from " + std::to_string(minimum) + " to " +
                                    std::to_string(largest) + ", got " + shown(value));
    return value.get<int>();
}

}  // namespace

EngineOptions parse_engine_options(const char* text) {
    EngineOptions options;
    std::string backend = "auto";
    if (text && *text) {
        nlohmann::json doc;
        try {
            doc = nlohmann::json::parse(text);
        } catch (const nlohmann::json::exception& e) {
            // parse_error, and out_of_range for a number no double holds (1e7662).
            throw Error(STRUCTMD_ERR_ARGUMENT, std::string("options: not valid JSON: ") + e.what());
        }
        if (!doc.is_object()) throw Error(STRUCTMD_ERR_ARGUMENT, "options: expected a JSON object");
        for (const auto& [key, value] : doc.items()) {
            if (key == "backend") {
                backend = string_option(value, key);
                if (backend != "auto" && backend != "cpu" && backend != "cuda")
                    throw option_error(key, "expected \"auto\", \"cpu\" or \"cuda\", got \"" + backend + "\"");
            } else if (key == "device") {
                options.device = int_option(value, key, 0);
                options.deviceGiven = true;
            } else if (key == "precision") {
                const std::string precision = string_option(value, key);
                if (precision == "single") options.precision = Precision::single;
                else if (precision == "mixed") options.precision = Precision::mixed;
                else if (precision == "double") options.precision = Precision::double_;
                else throw option_error(key, "expected \"single\", \"mixed\" or \"double\", got \"" + precision + "\"");
                if (!precision_compiled(options.precision))
                    throw Error(STRUCTMD_ERR_UNSUPPORTED, "option \"precision\": this build of structmd has no " + precision +
                                                              " precision engines (built: " + compiled_precision_names() +
                                                              "; CMake option STRUCTMD_PRECISIONS)");
            } else if (key == "threads") {
                options.threads = int_option(value, key, 1);
            } else if (key == "log") {
                const std::string level = string_option(value, key);
                if (level == "quiet") options.logLevel = LogLevel::quiet;
                else if (level == "warning") options.logLevel = LogLevel::warning;
                else if (level == "info") options.logLevel = LogLevel::info;
                else if (level == "debug") options.logLevel = LogLevel::debug;
                else throw option_error(key, "expected \"quiet\", \"warning\", \"info\" or \"debug\", got \"" + level + "\"");
            } else if (key == "log_file") {
                options.logFile = string_option(value, key);
            } else if (key == "plugins") {
                if (!value.is_array()) throw option_error(key, "expected an array of paths, got " + shown(value));
                for (const auto& path : value) options.plugins.push_back(string_option(path, key));
            } else if (key == "mpi_comm") {
                if (!value.is_number_integer())
                    throw option_error(key, "expected an integer (a Fortran communicator handle, MPI_Comm_c2f), got " +
                                                shown(value));
                options.mpiComm = value.get<int64_t>();
            } else if (key == "ghost_exchange") {
                const std::string how = string_option(value, key);
                if (how == "auto") options.ghostExchange = EngineOptions::GhostExchange::automatic;
                else if (how == "host") options.ghostExchange = EngineOptions::GhostExchange::host;
                else if (how == "nccl") options.ghostExchange = EngineOptions::GhostExchange::nccl;
                else throw option_error(key, "expected \"auto\", \"host\" or \"nccl\", got \"" + how + "\"");
            } else if (key == "pair_traversal") {
                const std::string how = string_option(value, key);
                if (how == "auto") options.pairTraversal = EngineOptions::PairTraversal::automatic;
                else if (how == "clusters") options.pairTraversal = EngineOptions::PairTraversal::clusters;
                else if (how == "particles") options.pairTraversal = EngineOptions::PairTraversal::particles;
                else throw option_error(key, "expected \"auto\", \"clusters\" or \"particles\", got \"" + how + "\"");
            } else if (key == "step_graphs") {
                if (!value.is_boolean()) throw option_error(key, "expected true or false, got " + shown(value));
                options.stepGraphs = value.get<bool>();
            } else {
                throw option_error(key, "unknown option (known: backend, device, precision, threads, log, log_file, "
                                        "plugins, mpi_comm, ghost_exchange, pair_traversal, step_graphs)");
            }
        }
    }
    if (backend == "auto") {
        options.backend = usable_gpu_count() > 0 ? BackendKind::cuda : BackendKind::cpu;
    } else if (backend == "cuda") {
        if (const std::string why = cuda_backend_unavailable(); !why.empty())
            throw Error(STRUCTMD_ERR_UNSUPPORTED, "option \"backend\": " + why);
        const int gpus = usable_gpu_count();
        if (gpus == 0) throw Error(STRUCTMD_ERR_DEVICE, "option \"backend\": \"cuda\" was asked for but no usable GPU was found");
        if (options.device >= gpus)
            throw option_error("device", "GPU " + std::to_string(options.device) + " does not exist (found " +
                                             std::to_string(gpus) + ")");
        options.backend = BackendKind::cuda;
    } else {
        options.backend = BackendKind::cpu;
    }
    if (options.ghostExchange == EngineOptions::GhostExchange::nccl) {
        if (!nccl_compiled())
            throw Error(STRUCTMD_ERR_UNSUPPORTED, "option \"ghost_exchange\": this build of structmd has no NCCL "
                                                  "(it needs CUDA, MPI and NCCL when it is built)");
        if (options.backend != BackendKind::cuda)
            throw option_error("ghost_exchange", "\"nccl\" sends ghosts between GPUs, and the backend is the CPU");
    }
    return options;
}

bool cluster_pairs(const EngineOptions& options) {
    switch (options.pairTraversal) {
        case EngineOptions::PairTraversal::clusters: return true;
        case EngineOptions::PairTraversal::particles: return false;
        // Per-particle lists were 2.3x faster on an H200 at 10,976 and 1,000,188 particles
        // (docs/benchmarks.md, "Cluster pairs"), and are on the CPU too.
        case EngineOptions::PairTraversal::automatic: return false;
    }
    return false;
}

}  // namespace structmd
