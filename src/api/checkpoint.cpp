// Saving and restoring the dynamic state.
#include "api/handle.hpp"

using namespace structmd;
using namespace structmd::api;

extern "C" {

structmd_status structmd_save_checkpoint(structmd_sim* sim, const char* path) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        require_pointer(path, "path");
        simulation.save_checkpoint(path);
    });
}

structmd_status structmd_load_checkpoint(structmd_sim* sim, const char* path) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        require_pointer(path, "path");
        simulation.load_checkpoint(path);
    });
}

}  // extern "C"
