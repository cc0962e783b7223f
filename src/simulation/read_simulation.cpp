#include "simulation/read_simulation.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "steps/backup_step.hpp"

#include "forcefield/read_forcefield.hpp"
#include "input/description.hpp"
#include "integrators/read_integrators.hpp"
#include "steps/read_simulation_steps.hpp"

namespace structmd {


SimulationSpec read_simulation(const std::string& text, const Logger& log) {
    input::ParsedDocument doc = input::parse_document(text);
    const input::SystemDescription& system = doc.system;

    SimulationSpec spec;
    spec.forceField = read_forcefield(system, log);
    spec.integrators = read_integrators(system, spec.schedule);
    const auto& groups = spec.forceField.groups;
    for (const IntegratorSpec& integrator : spec.integrators) {
        const GroupSpec* group = nullptr;
        if (!integrator.group.empty()) {
            auto it = std::find_if(groups.begin(), groups.end(), [&](const GroupSpec& g) { return g.name == integrator.group; });
            if (it == groups.end())
                throw input_error(integrator.path + ".parameters.group",
                                  "no group named '" + integrator.group + "' (define it in a [\"Groups\", \"GroupsList\"] entry)");
            group = &*it;
        }
        // Brownian mobility is 1 / (6 pi eta a): every particle it moves needs a radius.
        if (integrator.kind == "EulerMaruyama")
            for (int64_t i = 0; i < system.numParticles(); ++i)
                if ((!group || group->members[i]) && !(system.radius[i] > 0.0))
                    throw input_error(integrator.path, "particle id " + std::to_string(i) +
                                                           " has radius " + std::to_string(system.radius[i]) +
                                                           ": Brownian dynamics needs a positive radius");
    }
    spec.steps = read_simulation_steps(system, spec.forceField.groups, log);
    if (const auto& b = system.backup)
        spec.steps.push_back(std::make_unique<BackupStep>(b->intervalStep, b->startStep, b->endStep, b->filePath));
    doc.root.check_all_used();

    spec.seed = system.seed;
    spec.constants.boltzmann = system.units.boltzmann;
    spec.constants.electricConversion = system.units.electricConversion;
    spec.velocityKT = spec.schedule.empty() ? system.units.boltzmann * system.temperature
                                            : spec.integrators[spec.schedule.front().integrator].temperature;
    spec.box = system.box;
    spec.currentStep = system.currentStep;
    spec.simulationTime = system.simulationTime;
    for (const input::ParticleType& type : system.types) spec.typeNames.push_back(type.name);
    spec.positions = system.positions;
    spec.velocities = system.velocities;
    spec.typeIndex = system.typeIndex;
    spec.mass = system.mass;
    spec.radius = system.radius;
    spec.charge = system.charge;
    spec.batchId = system.batchId;
    spec.modelId = system.modelId;
    return spec;
}

}  // namespace structmd
