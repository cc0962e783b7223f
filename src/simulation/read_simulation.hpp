#pragma once
#include <string>

#include "core/logger.hpp"
#include "simulation/simulation_spec.hpp"

namespace structmd {

// Parses and validates a whole input document into a SimulationSpec. Every key of the document must
// be used by some component; throws Error(ERR_INPUT) naming the path otherwise.
SimulationSpec read_simulation(const std::string& text, const Logger& log);

}  // namespace structmd
