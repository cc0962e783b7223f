#include "simulation/forwarding_simulation.hpp"

#include "core/error.hpp"

namespace structmd {

void ForwardingSimulation::admit(Operation op, PerParticle quantity) const {
    const std::string what = refusal(op, quantity);
    if (!what.empty()) throw Error(STRUCTMD_ERR_UNSUPPORTED, what + " is not available " + refusal_reason());
}

}  // namespace structmd
