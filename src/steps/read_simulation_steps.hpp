#pragma once
#include <memory>
#include <vector>

#include "input/description.hpp"
#include "steps/simulation_step.hpp"

namespace structmd {

// Builds the simulationStep entries. Throws Error(ERR_INPUT) naming the path for an unknown step
// or a bad interval, and Error(ERR_IO) when an output file cannot be opened.
std::vector<std::unique_ptr<SimulationStep>> read_simulation_steps(const input::SystemDescription& system);

}  // namespace structmd
