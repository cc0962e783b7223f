#pragma once
#include <vector>

#include "forcefield/forcefield_spec.hpp"
#include "input/description.hpp"
#include "integrators/integrator_spec.hpp"

namespace structmd {

// Reads the integrator section and the schedule through the integrator registry. Throws
// Error(ERR_INPUT) naming the path of an unknown integrator, a bad parameter, an unknown group or a
// particle without the radius an integrator needs.
std::vector<IntegratorSpec> read_integrators(const input::SystemDescription& system,
                                             const std::vector<GroupSpec>& groups,
                                             std::vector<ScheduleStage>& schedule,
                                             const Registry<IntegratorComponent>& registry = integrator_registry());

}  // namespace structmd
