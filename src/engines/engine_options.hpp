#pragma once
// Options of structmd_create, validated: the backend and precision every load of a handle uses.
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/logger.hpp"
#include "engines/engine_kind.hpp"

namespace structmd {

struct EngineOptions {
    BackendKind backend = BackendKind::cpu;  // "auto" resolved
    int device = 0;
    bool deviceGiven = false;  // "device" was given: under "mpi_comm" the ranks do not choose their own
    Precision precision = default_precision();
    int threads = 0;  // 0: all the OpenMP runtime offers
    LogLevel logLevel = LogLevel::warning;
    std::string logFile;  // empty: standard error
    std::vector<std::string> plugins;  // plugin libraries this handle loads, beside the process-wide ones
    // The host's MPI communicator as a Fortran handle (MPI_Comm_c2f), over whose ranks the handle
    // spreads the batches of its inputs (parallel/); empty: no MPI.
    std::optional<int64_t> mpiComm;
    // How spatial domains send their ghosts: "auto" (from GPU to GPU where NCCL is compiled in and the
    // backend is CUDA, else through the host), "host" (MPI over host memory) or "nccl".
    enum class GhostExchange { automatic, host, nccl } ghostExchange = GhostExchange::automatic;
    // How pair terms walk their neighbours: "auto" (per-particle lists, the faster today on both
    // backends), "clusters" or "particles" (neighbour/cluster_view.hpp). Lists with a condition,
    // exclusions or batches, and spatial domains, always use per-particle lists.
    enum class PairTraversal { automatic, clusters, particles } pairTraversal = PairTraversal::automatic;
    // Whether the CUDA backend runs the steps of a call as CUDA graphs (the default). Without them
    // each kernel is launched as it comes: slower at small N, for profilers and debuggers (Nsight
    // Compute cannot time the kernels of a graph with conditional nodes).
    bool stepGraphs = true;
};

// Parses the options JSON (NULL or "" for defaults) and resolves "auto". Throws Error(ERR_ARGUMENT)
// for unknown keys or bad values, ERR_DEVICE / ERR_UNSUPPORTED when "cuda" cannot be had.
EngineOptions parse_engine_options(const char* json);


// Whether this build sends spatial domains' ghosts between GPUs through NCCL (CMake STRUCTMD_NCCL).
constexpr bool nccl_compiled() {
#ifdef STRUCTMD_HAVE_NCCL
    return true;
#else
    return false;
#endif
}

// What the options run on, before any simulation is loaded.
std::string device_description(const EngineOptions& options);
int cpu_thread_count(const EngineOptions& options);

// Whether the pair terms of a simulation made with these options may walk cluster pairs.
bool cluster_pairs(const EngineOptions& options);

}  // namespace structmd
