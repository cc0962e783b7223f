#pragma once
#include <string>

#include "core/logger.hpp"
#include "forcefield/component_registry.hpp"
#include "simulation/simulation_spec.hpp"

namespace structmd {

// Parses and validates a whole input document into a SimulationSpec, reading topology.forceField
// with `components` (the built-ins, or a handle's registry with its plugins' components). Every key
// of the document must be used by some component; throws Error(ERR_INPUT) naming the path otherwise.
SimulationSpec read_simulation(const std::string& text, const Logger& log,
                               const Registry<ForceFieldComponent>& components = forcefield_registry());

}  // namespace structmd
