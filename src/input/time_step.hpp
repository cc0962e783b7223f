#pragma once
// The time step an integrator steps with, read in this one place so that every component that
// depends on it (the integrators, AFM's chip, the trajectory writers) agrees: the integrator's own
// parameters.timeStep, else global.fundamental's.
#include <optional>

#include "input/description.hpp"

namespace structmd::input {

// The integrator entry's own timeStep, else global.fundamental's; empty when neither gives one.
// Throws an input error at <entry>.parameters.timeStep for one that is not a positive number.
std::optional<double> time_step_of(const ComponentEntry& integrator, const SystemDescription& system);

// The time step of the integrator that runs the first step: that of the first schedule row with
// steps, else of the last row, which goes on past the schedule's end (simulation/schedule.hpp);
// global.fundamental's when the schedule names no integrator.
std::optional<double> first_time_step(const SystemDescription& system);

}  // namespace structmd::input
