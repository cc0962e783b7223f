// The host's force callbacks: C function pointers and user data wrapped into the engine's
// HostForceCallback and DeviceForceCallback, a failure of which becomes an Error with status
// STRUCTMD_ERR_CALLBACK and the host's own words.
#include <exception>
#include <string>

#include "api/handle.hpp"

using namespace structmd;
using namespace structmd::api;

namespace {

// Marks the handle as inside a callback for structmd_set_callback_error, and clears that mark on the
// way out, a throw included.
class CallbackScope {
public:
    explicit CallbackScope(structmd_sim& sim) : sim_(sim) {
        sim_.callbackError.clear();
        sim_.inCallback = true;
    }
    ~CallbackScope() { sim_.inCallback = false; }
    CallbackScope(const CallbackScope&) = delete;
    CallbackScope& operator=(const CallbackScope&) = delete;

private:
    structmd_sim& sim_;
};

// Calls the host's function; a non-zero status or an exception of a C++ host becomes ERR_CALLBACK.
template <class Call>
void call_host(structmd_sim& sim, const char* which, int64_t step, Call&& call) {
    const std::string where = "step " + std::to_string(step) + ": the " + which;
    int32_t status = 0;
    {
        CallbackScope scope(sim);
        const HostLocaleScope hostLocale;
        try {
            status = call();
        } catch (const std::exception& e) {
            throw Error(STRUCTMD_ERR_CALLBACK, where + " threw: " + e.what());
        } catch (...) {
            throw Error(STRUCTMD_ERR_CALLBACK, where + " threw an exception that is not a std::exception");
        }
    }
    if (status != 0)
        throw Error(STRUCTMD_ERR_CALLBACK, where + " returned " + std::to_string(status) +
                                               (sim.callbackError.empty() ? "" : ": " + sim.callbackError));
}

}  // namespace

extern "C" {

structmd_status structmd_set_force_callback(structmd_sim* sim, structmd_force_callback callback, void* user_data) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        if (!callback) {
            simulation.set_force_callback(HostForceCallback());
            return;
        }
        structmd_sim* handle = &s;
        simulation.set_force_callback(HostForceCallback([handle, callback, user_data](const HostForceCall& c) {
            call_host(*handle, "force callback", c.step, [&] {
                return callback(c.positions, c.forces, c.n, c.energy, c.virial, c.step, user_data);
            });
        }));
    });
}

structmd_status structmd_set_device_force_callback(structmd_sim* sim, structmd_device_force_callback callback,
                                                   void* user_data) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        if (!callback) {
            simulation.set_force_callback(DeviceForceCallback());
            return;
        }
        structmd_sim* handle = &s;
        simulation.set_force_callback(DeviceForceCallback([handle, callback, user_data](const DeviceForceCall& c) {
            call_host(*handle, "device force callback", c.step, [&] {
                return callback(c.positions, c.forces, c.n, c.realSize, c.energy, c.virial, c.step, c.stream,
                                user_data);
            });
        }));
    });
}

structmd_status structmd_set_callback_error(structmd_sim* sim, const char* message) {
    return with_handle(
        sim,
        [&](structmd_sim& s) {
            require_pointer(message, "message");
            if (s.inCallback) s.callbackError = message;
        },
        true);
}

}  // extern "C"
