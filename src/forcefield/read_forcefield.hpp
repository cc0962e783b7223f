#pragma once
#include "core/logger.hpp"
#include "forcefield/component_registry.hpp"
#include "forcefield/forcefield_spec.hpp"
#include "input/description.hpp"

namespace structmd {

// Reads every topology.forceField entry through the component registry. Throws Error(ERR_INPUT)
// naming the path for an unknown component, a bad parameter, a bond to a missing particle or a
// cutoff longer than half the box.
ForceFieldSpec read_forcefield(const input::SystemDescription& system, const Logger& log,
                               const Registry<ForceFieldComponent>& registry = forcefield_registry());

// The ["VerletConditionalListSet", condition] names the reader knows, for the check that each is
// documented (an unknown one's message names only the nearest few).
std::vector<ComponentKey> neighbour_list_keys();

// The units' constants, the largest particle radius (its type's or the state's), which potentials
// of radii scale their range with, and the ensemble's temperature; the reader and the engines must
// see the same.
Constants constants_of(const input::SystemDescription& system);

}  // namespace structmd
