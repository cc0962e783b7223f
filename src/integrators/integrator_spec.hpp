#pragma once
// Integrators and their schedule as read from the integrator section: plain data.
#include <cstdint>
#include <string>
#include <vector>

namespace structmd {

struct IntegratorSpec {
    std::string name;
    std::string path;
    std::string kind;  // VelocityVerlet, BBK, GJF, EulerMaruyama or SteepestDescent
    double timeStep = 0.0;
    double temperature = 0.0;  // k_B T, in energy units
    std::string group;         // empty: every particle
    double frictionConstant = 0.0;   // Langevin
    bool resetVelocities = true;     // Langevin
    double viscosity = 0.0;          // Brownian
    double h = 0.0;                  // SteepestDescent: initial step
    double maxObjectiveForce = 0.0;  // SteepestDescent
};

struct ScheduleStage {
    int integrator = 0;  // index into the integrator list
    int64_t steps = 0;
};

}  // namespace structmd
