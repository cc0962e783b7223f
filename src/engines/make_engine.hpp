#pragma once
// The composition root: the one place where an engine is built for a (backend, precision) pair.
// Nothing above this layer includes a backend, and nothing below it chooses one.
#include <memory>
#include <string>

#include "core/logger.hpp"
#include "engines/engine_options.hpp"
#include "forcefield/component_set.hpp"
#include "simulation/local_engine.hpp"
#include "simulation/simulation_spec.hpp"

namespace structmd {

// Reads an input document with the handle's force-field components (built-ins and its plugins') and
// builds its engine as the options say. Throws Error with the JSON path for bad input, ERR_DEVICE /
// ERR_MEMORY when the backend fails, ERR_UNSUPPORTED for a plugin component not compiled for the
// engine. firstParticleId: the global id of the document's particle 0 when it is a share of a larger
// system's batches (parallel/), which keys the particles' noise.
std::unique_ptr<LocalEngine> load_simulation(const EngineOptions& options, const std::string& text,
                                            const ForceFieldComponents& components, const Logger& log,
                                            int64_t firstParticleId = 0);

// Builds the engine of a spec already read (a spatial domain's, parallel/domain_spec.hpp).
std::unique_ptr<LocalEngine> make_simulation(const EngineOptions& options, SimulationSpec spec,
                                            const ForceFieldComponents& components, const Logger& log);

}  // namespace structmd
