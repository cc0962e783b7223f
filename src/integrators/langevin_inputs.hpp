#pragma once
// What both Langevin integrators (BBK, GJF) read: gamma, and whether velocities are drawn afresh at
// the Maxwell-Boltzmann distribution when their stage begins.
#include "integrators/integrator.hpp"

namespace structmd {

struct LangevinInputs : IntegratorInputs {
    static std::vector<Parameter> parameters() {
        return {with_default(number("frictionConstant", "1/time", Must::be_positive), 0.0),
                with_default(boolean("resetVelocities"), 1.0)};
    }
    static constexpr const char* fallbackParameter = "frictionConstant";
    static constexpr StateColumn fallbackColumn = StateColumn::frictionConstant;
};

}  // namespace structmd
