#pragma once
#include <memory>
#include <string>

#include "core/logger.hpp"
#include "forcefield/component_registry.hpp"
#include "input/description.hpp"
#include "simulation/simulation_spec.hpp"

namespace structmd {

class ForceFieldComponents;  // forcefield/component_set.hpp

// Parses and validates a whole input document into a SimulationSpec, reading topology.forceField
// with `components` (the built-ins, or a handle's with its plugins' components) and simulationStep
// with their transversers (["TransverserMeasure","Plugin"]). Every key of the document must be used
// by some component; throws Error(ERR_INPUT) naming the path otherwise.
SimulationSpec read_simulation(const std::string& text, const Logger& log, const ForceFieldComponents& components);
// The same from a document already parsed, for a caller that decides from its description first
// (parallel/load_over_ranks.cpp: one batch or several, which components run under domains).
SimulationSpec read_simulation(const input::ParsedDocument& document, const Logger& log,
                               const ForceFieldComponents& components);
// The same with the force field's reader registry alone (the parallel layouts that load through
// engines/make_engine.cpp): no transverser is known, and a ["TransverserMeasure","Plugin"] step is
// refused as unsupported there.
SimulationSpec read_simulation(const std::string& text, const Logger& log,
                               const Registry<ForceFieldComponent>& components = forcefield_registry());
SimulationSpec read_simulation(const input::ParsedDocument& document, const Logger& log,
                               const Registry<ForceFieldComponent>& components);

// What structmd_set_parameter may change, read again from the parsed document after a parameter in
// it changed: the force field and the integrators, validated as a load validates them (every key of
// their entries must be used). The particles are the description's; their tables are not read.
// The constants come again too: the ensemble's temperature may be what changed.
struct RuntimeSpec {
    Constants constants;
    ForceFieldSpec forceField;
    std::vector<IntegratorSpec> integrators;
    std::vector<ScheduleStage> schedule;
};
RuntimeSpec read_runtime_spec(const input::SystemDescription& system, const Logger& log,
                              const Registry<ForceFieldComponent>& components);

// The loaded input as structmd_set_parameter keeps it: parsed and checked once, its particle tables
// (state and structure data) emptied, since the engine holds the particles.
std::unique_ptr<input::ParsedDocument> read_parameter_document(const std::string& text);

}  // namespace structmd
