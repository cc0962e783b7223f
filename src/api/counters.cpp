// structmd_get_counters: what the engine has done since the load, as JSON.
#include <nlohmann/json.hpp>

#include "api/handle.hpp"

using namespace structmd;
using namespace structmd::api;

extern "C" {

structmd_status structmd_get_counters(structmd_sim* sim, char* buffer, size_t size) {
    return with_handle(sim, [&](structmd_sim& s) {
        const Counters c = loaded(s).counters();
        nlohmann::json counters;
        counters["force_evaluations"] = c.forceEvaluations;
        counters["energy_evaluations"] = c.energyEvaluations;
        counters["virial_evaluations"] = c.virialEvaluations;
        counters["neighbour_list_builds"] = c.neighbourListBuilds;
        counters["host_to_device_bytes"] = c.hostToDeviceBytes;
        counters["device_to_host_bytes"] = c.deviceToHostBytes;
        counters["device_memory_bytes"] = c.deviceMemoryBytes;
        counters["step_graphs_captured"] = c.stepGraphsCaptured;
        counters["step_graphs_replayed"] = c.stepGraphsReplayed;
        counters["domain_rebuilds"] = c.domainRebuilds;
        counters["steps_joined"] = c.stepsJoined;
        copy_text(counters.dump(), buffer, size);
    });
}

}  // extern "C"
