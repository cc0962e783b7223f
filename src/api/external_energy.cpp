// The energy of the host's own field, which the engine cannot compute: the host gives it, and it
// becomes the energy term "external", part of "total" and of the thermodynamic outputs.
#include <cmath>

#include "api/handle.hpp"

using namespace structmd;
using namespace structmd::api;

extern "C" {

structmd_status structmd_set_external_energy(structmd_sim* sim, double energy) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        if (!std::isfinite(energy)) throw Error(STRUCTMD_ERR_ARGUMENT, "energy: not a finite number");
        simulation.set_external_energy(energy);
    });
}

}  // extern "C"
