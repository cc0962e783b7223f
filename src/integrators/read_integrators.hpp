#pragma once
#include <vector>

#include "input/description.hpp"
#include "integrators/integrator_spec.hpp"

namespace structmd {

// Reads the integrator entries and resolves the schedule rows to them. Throws Error(ERR_INPUT)
// naming the path for an unknown integrator or a missing time step.
std::vector<IntegratorSpec> read_integrators(const input::SystemDescription& system,
                                             std::vector<ScheduleStage>& schedule);

}  // namespace structmd
