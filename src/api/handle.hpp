#pragma once
// What a structmd_sim handle holds, and the exception barrier every exported function goes through:
// the only place that catches, mapping each failure to a status and a per-handle message.
#include <cstdio>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "api/call_locale.hpp"
#include "core/error.hpp"
#include "core/logger.hpp"
#include "engines/engine_options.hpp"
#include "simulation/read_simulation.hpp"
#include "simulation/simulation.hpp"
#include "simulation/transverser_call.hpp"
#include "structmd.h"

namespace structmd {
class ForceFieldComponents;  // forcefield/component_set.hpp, reached through engines/make_engine.hpp
class Communicator;          // parallel/communicator.hpp
}

// A live handle's first word. structmd_destroy clears it before freeing the memory (where the
// allocator then keeps its own pointers), so that a handle used after destroy is refused for as long
// as the memory is not given to something else.
inline constexpr uint64_t kLiveHandle = 0x444d544355525453ull;  // the bytes "STRUCTMD"

struct structmd_sim {
    // volatile: the store of destroy, just before the memory is freed, must not be elided.
    volatile uint64_t liveness = kLiveHandle;
    structmd::EngineOptions options;
    // Built-ins, the plugins loaded process-wide before the handle was created, and those of its
    // "plugins" option. Fixed at creation; shared by every load of the handle.
    std::shared_ptr<const structmd::ForceFieldComponents> components;
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> logFile{nullptr, &std::fclose};
    structmd::Logger log;
    // The communicator of the "mpi_comm" option, whose ranks share the batches of each load; null
    // without one. The host owns MPI itself (MPI_Init, MPI_Finalize).
    std::shared_ptr<const structmd::Communicator> communicator;
    std::unique_ptr<structmd::Simulation> simulation;
    // The input the simulation was loaded from, kept as text until the first parameter call parses
    // it into runtimeDocument (parameters.cpp), which then holds the changes of structmd_set_parameter.
    std::string document;
    std::unique_ptr<structmd::input::ParsedDocument> runtimeDocument;
    // By particle id: the subset call that last named it (subsets.cpp), so a repeated id is found in
    // O(m) with no allocation after the first call.
    std::vector<uint64_t> idSeenAt;
    uint64_t subsetCalls = 0;
    // The last ids found distinct: a coupling loop names the same region call after call, and
    // comparing with them reads memory in order where the stamps above are scattered over n.
    std::vector<int64_t> distinctIds;
    // What a force callback said through structmd_set_callback_error while it ran (callbacks.cpp).
    std::string callbackError;
    bool inCallback = false;
    // The last registered transverser call, made from the host's arguments (transversers.cpp): a
    // loop that runs one transverser every step parses its parameters once. The components are
    // fixed at creation, so the same arguments always make the same call.
    struct {
        std::string name, parameters;
        double cutoff = 0;
        std::unique_ptr<const structmd::TransverserCall> call;
    } lastTransverser;
    std::string lastError;
};

namespace structmd::api {

// Message of the last failure on this thread that had no handle to hold it (a failed create, a
// NULL handle, structmd_load_plugin).
std::string& thread_error();

// The components of a new handle: built-ins, every plugin loaded by structmd_load_plugin so far, then
// `paths` (its "plugins" option) in order (plugins.cpp).
std::shared_ptr<const ForceFieldComponents> handle_components(const std::vector<std::string>& paths);

template <class Body>
structmd_status guarded(std::string& message, Body&& body) noexcept {
    const ClassicLocaleScope locale;
    try {
        body();
        return STRUCTMD_OK;
    } catch (const Error& e) {
        message = e.what();
        return e.status();
    } catch (const std::bad_alloc&) {
        message = "out of host memory";
        return STRUCTMD_ERR_MEMORY;
    } catch (const std::exception& e) {
        message = std::string("internal error, please report: ") + e.what();
        return STRUCTMD_ERR_INTERNAL;
    } catch (...) {
        message = "internal error, please report: unknown exception";
        return STRUCTMD_ERR_INTERNAL;
    }
}

// What a call on a handle says while one of its force callbacks runs: the engine is in the middle
// of an evaluation, which a load, a step, a getter that evaluates or a destroy would pull away.
inline const char* const kInsideCallback =
    "not available inside a force callback of this handle (only structmd_set_callback_error is)";

inline const char* const kNotLive = "sim: not a live handle (destroyed already?)";

// Runs body(handle) behind the barrier; a NULL or destroyed handle is STRUCTMD_ERR_ARGUMENT, a call
// from inside one of the handle's force callbacks STRUCTMD_ERR_STATE (unless insideCallbackAllowed).
template <class Handle, class Body>
structmd_status with_handle(Handle* sim, Body&& body, bool insideCallbackAllowed = false) noexcept {
    if (!sim) {
        thread_error() = "sim: NULL handle";
        return STRUCTMD_ERR_ARGUMENT;
    }
    if (sim->liveness != kLiveHandle) {
        thread_error() = kNotLive;
        return STRUCTMD_ERR_ARGUMENT;
    }
    structmd_sim& handle = *const_cast<structmd_sim*>(sim);
    if (handle.inCallback && !insideCallbackAllowed) {
        handle.lastError = kInsideCallback;
        return STRUCTMD_ERR_STATE;
    }
    return guarded(handle.lastError, [&] { body(*sim); });
}

// The loaded simulation, or ERR_STATE.
template <class Handle>
auto& loaded(Handle& sim) {
    if (!sim.simulation)
        throw Error(STRUCTMD_ERR_STATE,
                    "no simulation is loaded (call structmd_load_file or structmd_load_string first)");
    return *sim.simulation;
}

inline void require_pointer(const void* pointer, const char* name) {
    if (!pointer) throw Error(STRUCTMD_ERR_ARGUMENT, std::string(name) + ": NULL pointer");
}

// An array argument of n entries per particle: n must equal the particle count.
inline void require_count(const Simulation& simulation, int64_t n, const void* pointer, const char* name) {
    if (n != simulation.particle_count())
        throw Error(STRUCTMD_ERR_ARGUMENT, "n: expected " + std::to_string(simulation.particle_count()) +
                                               " (the number of particles), got " + std::to_string(n));
    require_pointer(pointer, name);
}

// Copies text and its NUL into a caller's buffer of size bytes, or fails naming the size needed.
inline void copy_text(const std::string& text, char* buffer, size_t size) {
    if (size < text.size() + 1)
        throw Error(STRUCTMD_ERR_ARGUMENT,
                    "size: the buffer needs " + std::to_string(text.size() + 1) + " bytes, got " + std::to_string(size));
    require_pointer(buffer, "buffer");
    std::memcpy(buffer, text.c_str(), text.size() + 1);
}

}  // namespace structmd::api
