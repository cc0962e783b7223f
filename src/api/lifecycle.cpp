// Version queries, handle creation and destruction, errors and loading.
#include <cerrno>
#include <cstring>

#include "api/handle.hpp"
#include "core/regular_file.hpp"
#include "engines/devices.hpp"
#include "engines/make_engine.hpp"
#include "parallel/load_over_ranks.hpp"

namespace structmd::api {

std::string& thread_error() {
    thread_local std::string message;
    return message;
}

namespace {

// All or nothing: the new simulation is built beside the loaded one, which a failure leaves in place
// and usable (a host's mistyped reload must not lose a long run). Both are in memory meanwhile.
void load_text(structmd_sim& sim, const std::string& text) {
    std::unique_ptr<Simulation> replacement = load_over_ranks(sim.options, text, *sim.components, sim.log,
                                                              sim.communicator ? sim.communicator : single_process());
    std::string document = text;
    sim.simulation = std::move(replacement);  // moves, which cannot fail: the swap is whole
    sim.document = std::move(document);
    sim.runtimeDocument.reset();
    const EngineDescription description = sim.simulation->description();
    sim.log.info("loaded " + std::to_string(sim.simulation->particle_count()) + " particles on " +
                 description.backend + " (" + description.device + "), " + description.precision + " precision");
}

}  // namespace
}  // namespace structmd::api

using namespace structmd;
using namespace structmd::api;

extern "C" {

int structmd_abi_version(void) { return STRUCTMD_ABI_VERSION; }

const char* structmd_version(void) { return STRUCTMD_VERSION_STRING; }

structmd_status structmd_create(const char* options_json, structmd_sim** out) {
    return guarded(thread_error(), [&] {
        require_pointer(out, "out");
        *out = nullptr;
        auto sim = std::make_unique<structmd_sim>();
        sim->options = parse_engine_options(options_json);
        sim->components = handle_components(sim->options.plugins);
        if (sim->options.mpiComm) {
            sim->communicator = communicator_from_fortran(*sim->options.mpiComm);
            // One GPU per rank on a node with several, as mpirun places ranks node by node.
            if (sim->options.backend == BackendKind::cuda && !sim->options.deviceGiven)
                sim->options.device = sim->communicator->node_rank() % usable_gpu_count();
        }
        std::FILE* sink = stderr;
        if (!sim->options.logFile.empty()) {
            sim->logFile.reset(std::fopen(sim->options.logFile.c_str(), "a"));
            if (!sim->logFile)
                throw Error(STRUCTMD_ERR_IO, "option \"log_file\": cannot open '" + sim->options.logFile +
                                                 "': " + std::strerror(errno));
            sink = sim->logFile.get();
        }
        sim->log = Logger(sim->options.logLevel, sink);
        *out = sim.release();
    });
}

void structmd_destroy(structmd_sim* sim) {
    // Destructors release device memory; a failing CUDA call there must not escape either.
    if (sim && sim->liveness != kLiveHandle) {
        thread_error() = std::string("structmd_destroy: ") + kNotLive;
        return;
    }
    if (sim && sim->inCallback) {
        // Deleting the engine that is calling the host would leave it running on freed memory.
        sim->lastError = thread_error() = std::string("structmd_destroy: ") + kInsideCallback;
        return;
    }
    if (sim) sim->liveness = 0;
    guarded(thread_error(), [&] { delete sim; });
}

const char* structmd_last_error(const structmd_sim* sim) {
    if (sim && sim->liveness != kLiveHandle) return kNotLive;
    return sim ? sim->lastError.c_str() : thread_error().c_str();
}

structmd_status structmd_load_file(structmd_sim* sim, const char* path) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_pointer(path, "path");
        const FileContents file = read_regular_file(path);
        if (!file.problem.empty()) throw Error(STRUCTMD_ERR_IO, std::string("'") + path + "': " + file.problem);
        load_text(s, file.bytes);
    });
}

structmd_status structmd_load_string(structmd_sim* sim, const char* json) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_pointer(json, "json");
        load_text(s, json);
    });
}

}  // extern "C"
