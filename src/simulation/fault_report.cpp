#include "simulation/fault_report.hpp"

#include "state/fault.hpp"

namespace structmd {

std::string describe_fault(unsigned long long word, double skin, int64_t failedStep, int64_t backAt) {
    std::string what;
    switch (FaultSlot::quantity_of(word)) {
        case FaultQuantity::position: what = "the position is not finite"; break;
        case FaultQuantity::velocity: what = "the velocity is not finite"; break;
        case FaultQuantity::force: what = "the force is not finite"; break;
        case FaultQuantity::displacement:
            what = "the displacement in one step is longer than the neighbour-list skin (" + std::to_string(skin) + ")";
            break;
        case FaultQuantity::mobility:
            what = "the hydrodynamic mobility matrix is not positive definite (its Cholesky factorisation failed)";
            break;
    }
    return "step " + std::to_string(FaultSlot::step_of(word)) + ", particle id " +
           std::to_string(FaultSlot::particle_of(word)) + ": " + what +
           ": the simulation blew up (time step too large, or overlapping particles); the run went on to step " +
           std::to_string(failedStep) + ", and the state is back at step " + std::to_string(backAt) +
           ", where this call started: repair it (structmd_set_positions, structmd_set_velocities, a checkpoint) or "
           "step on with a smaller time step";
}

}  // namespace structmd
