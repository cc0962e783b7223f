#include "integrators/read_integrators.hpp"

#include <cmath>

#include "core/error.hpp"

namespace structmd {

std::vector<IntegratorSpec> read_integrators(const input::SystemDescription& system,
                                             std::vector<ScheduleStage>& schedule) {
    std::vector<IntegratorSpec> integrators;
    for (const input::ComponentEntry& entry : system.integrators) {
        IntegratorSpec spec;
        spec.name = entry.name;
        spec.path = entry.node.path();
        if (entry.cls == "Verlet" && entry.subclass == "VelocityVerlet") {
            spec.kind = "VelocityVerlet";
        } else {
            throw input_error(spec.path + ".type", "unknown integrator [\"" + entry.cls + "\", \"" + entry.subclass +
                                                       "\"]; known: [\"Verlet\", \"VelocityVerlet\"]");
        }
        auto params = entry.node.find("parameters");
        std::optional<double> dt = system.timeStep;
        if (params) {
            if (auto own = params->find("timeStep")) dt = own->as<double>();
        }
        if (!dt) throw input_error(spec.path + ".parameters.timeStep",
                                   "missing time step (give it here or in global.fundamental)");
        if (!(*dt > 0.0) || !std::isfinite(*dt))
            throw input_error(spec.path + ".parameters.timeStep", "expected a positive time step");
        spec.timeStep = *dt;
        double temperature = system.temperature;
        if (params) temperature = params->get_or<double>("temperature", temperature);
        spec.temperature = system.units.boltzmann * temperature;
        integrators.push_back(spec);
    }
    schedule.clear();
    for (const input::ScheduleRow& row : system.schedule) {
        ScheduleStage stage;
        for (size_t k = 0; k < integrators.size(); ++k)
            if (integrators[k].name == row.integrator) stage.integrator = static_cast<int>(k);
        stage.steps = row.steps;
        schedule.push_back(stage);
    }
    return integrators;
}

}  // namespace structmd
