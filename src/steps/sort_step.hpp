#pragma once
// ["UtilsStep","SortStep"]: UAMMD-structured reorders its particle arrays along a space-filling curve
// for memory locality. structmd's neighbour lists already keep the particles they traverse sorted by
// cell, refreshed at every list build, so the step is accepted (inputs that schedule it load),
// schedules nothing, and says so in the log.
#include "steps/simulation_step_registry.hpp"

namespace structmd {

SimulationStepEntry sort_step_entry();

}  // namespace structmd
