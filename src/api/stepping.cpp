// Advancing time and evaluating without advancing.
#include <algorithm>
#include <cstdint>

#include "api/handle.hpp"

using namespace structmd;
using namespace structmd::api;

extern "C" {

structmd_status structmd_step(structmd_sim* sim, int64_t nsteps) {
    return with_handle(sim, [&](structmd_sim& s) { loaded(s).advance(nsteps); });
}

structmd_status structmd_run(structmd_sim* sim) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        simulation.advance(std::max<int64_t>(0, simulation.final_step() - simulation.current_step()));
    });
}

structmd_status structmd_compute(structmd_sim* sim, uint32_t flags) {
    return with_handle(sim, [&](structmd_sim& s) {
        const uint32_t known = STRUCTMD_FORCES | STRUCTMD_ENERGY | STRUCTMD_VIRIAL;
        if (flags & ~known)
            throw Error(STRUCTMD_ERR_ARGUMENT, "flags: unknown bits " + std::to_string(flags & ~known) +
                                                   " (known: STRUCTMD_FORCES, STRUCTMD_ENERGY, STRUCTMD_VIRIAL)");
        loaded(s).compute(flags);
    });
}

}  // extern "C"
