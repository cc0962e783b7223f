#pragma once
// What both Langevin integrators (BBK, GJF) read: gamma, and whether velocities are drawn afresh at
// the Maxwell-Boltzmann distribution when their stage begins.
#include "integrators/integrator.hpp"

namespace structmd {

struct LangevinInputs : IntegratorInputs {
    static std::vector<Parameter> parameters() {
        return {number("frictionConstant", "1/time", Must::be_positive), with_default(boolean("resetVelocities"), 1.0)};
    }
};

}  // namespace structmd
