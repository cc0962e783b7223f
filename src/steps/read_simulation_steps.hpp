#pragma once
#include <memory>
#include <vector>

#include "core/logger.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "input/description.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

// Builds the simulationStep entries from the steps of `registry`. groups: those of the force field,
// which a step's `group` names; log: the handle's log, which ["UtilsStep","InfoStep"] writes to.
// Throws Error(ERR_INPUT) naming the path for an unknown step (<entry>.type, with the known ones), a
// bad or missing parameter (<entry>.parameters.<name>) or an unknown group, and Error(ERR_UNSUPPORTED)
// for a group on a step that cannot restrict itself to one.
// forceField: its groups name what steps measure; its bonds are written by the PDB format.
// components: the handle's, whose plugins' transversers ["TransverserMeasure","Plugin"] runs; null
// where the reader was given no transversers (that step is then refused as unsupported).
std::vector<std::unique_ptr<SimulationStep>> read_simulation_steps(const Registry<SimulationStepEntry>& registry,
                                                                   const input::SystemDescription& system,
                                                                   const ForceFieldSpec& forceField,
                                                                   const ForceFieldComponents* components,
                                                                   const Logger& log);

// The same with the built-in steps (simulation_step_registry()).
std::vector<std::unique_ptr<SimulationStep>> read_simulation_steps(const input::SystemDescription& system,
                                                                   const ForceFieldSpec& forceField,
                                                                   const ForceFieldComponents* components,
                                                                   const Logger& log);

}  // namespace structmd
