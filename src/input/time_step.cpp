#include "input/time_step.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "input/read_parameters.hpp"

namespace structmd::input {

std::optional<double> time_step_of(const ComponentEntry& integrator, const SystemDescription& system) {
    const TrackedNode parameters = parameters_of(integrator.node);
    const std::optional<TrackedNode> own = parameters.valid() ? parameters.find("timeStep") : std::nullopt;
    if (!own) return system.timeStep;
    const double timeStep = own->as<double>();
    if (!(timeStep > 0.0) || !std::isfinite(timeStep)) throw input_error(own->path(), "expected a positive time step");
    return timeStep;
}

std::optional<double> first_time_step(const SystemDescription& system) {
    if (system.schedule.empty()) return system.timeStep;
    const auto running = std::find_if(system.schedule.begin(), system.schedule.end(),
                                      [](const ScheduleRow& row) { return row.steps > 0; });
    const ScheduleRow& first = running != system.schedule.end() ? *running : system.schedule.back();
    for (const ComponentEntry& integrator : system.integrators)
        if (integrator.name == first.integrator) return time_step_of(integrator, system);
    return system.timeStep;
}

}  // namespace structmd::input
