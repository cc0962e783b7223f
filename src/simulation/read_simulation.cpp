#include "simulation/read_simulation.hpp"

#include "core/error.hpp"
#include "steps/backup_step.hpp"

#include "forcefield/component_set.hpp"
#include "forcefield/read_forcefield.hpp"
#include "input/description.hpp"
#include "integrators/read_integrators.hpp"
#include "simulation/whole_molecules.hpp"
#include "steps/read_simulation_steps.hpp"

namespace structmd {

namespace {

// transversers: null where only the reader registry was given.
SimulationSpec read_document(const input::ParsedDocument& doc, const Logger& log,
                             const Registry<ForceFieldComponent>& components, const ForceFieldComponents* transversers) {
    const input::SystemDescription& system = doc.system;
    for (const std::string& warning : system.warnings) log.warning(warning);

    SimulationSpec spec;
    spec.forceField = read_forcefield(system, log, components);
    spec.integrators = read_integrators(system, spec.forceField.groups, spec.schedule);
    spec.steps = read_simulation_steps(system, spec.forceField, transversers, log);
    if (const auto& b = system.backup)
        spec.steps.push_back(std::make_unique<BackupStep>(b->intervalStep, b->startStep, b->endStep, b->filePath));
    doc.root.check_all_used();

    spec.seed = system.seed;
    spec.constants = constants_of(system);
    // Particles that start under overdamped dynamics start at rest: they have no velocities.
    if (spec.schedule.empty())
        spec.velocityKT = system.units.boltzmann * system.temperature;
    else if (const IntegratorSpec& first = spec.integrators[spec.schedule.front().integrator]; !first.overdamped)
        spec.velocityKT = first.temperature;
    spec.box = system.box;
    spec.lambda = system.lambda.value_or(1.0);
    spec.currentStep = system.currentStep;
    spec.simulationTime = system.simulationTime;
    for (const input::ParticleType& type : system.types) spec.typeNames.push_back(type.name);
    spec.positions = system.positions;
    make_bonded_groups_whole(spec.positions, spec.box, spec.forceField.bonds);
    spec.velocities = system.velocities;
    spec.typeIndex = system.typeIndex;
    spec.mass = system.mass;
    spec.radius = system.radius;
    spec.charge = system.charge;
    spec.orientations = system.orientations;
    spec.magnetizations = system.magnetizations;
    for_each_state_column([&](StateColumn c) {
        if (traits(c).onBackend) spec.columns[c] = system.stateColumns[c];
    });
    spec.batchId = system.batchId;
    spec.modelId = system.modelId;
    return spec;
}

}  // namespace

SimulationSpec read_simulation(const std::string& text, const Logger& log, const ForceFieldComponents& components) {
    return read_simulation(input::parse_document(text), log, components);
}

SimulationSpec read_simulation(const input::ParsedDocument& doc, const Logger& log,
                               const ForceFieldComponents& components) {
    return read_document(doc, log, components.reader(), &components);
}

SimulationSpec read_simulation(const std::string& text, const Logger& log,
                               const Registry<ForceFieldComponent>& components) {
    return read_simulation(input::parse_document(text), log, components);
}

SimulationSpec read_simulation(const input::ParsedDocument& doc, const Logger& log,
                               const Registry<ForceFieldComponent>& components) {
    return read_document(doc, log, components, nullptr);
}

std::unique_ptr<input::ParsedDocument> read_parameter_document(const std::string& text) {
    auto parsed = std::make_unique<input::ParsedDocument>(input::parse_document(text));
    nlohmann::json& doc = parsed->tracking->document;
    doc["state"]["data"] = nlohmann::json::array();
    doc["topology"]["structure"]["data"] = nlohmann::json::array();
    return parsed;
}

RuntimeSpec read_runtime_spec(const input::SystemDescription& system, const Logger& log,
                              const Registry<ForceFieldComponent>& components) {
    RuntimeSpec spec;
    spec.constants = constants_of(system);
    spec.forceField = read_forcefield(system, log, components);
    spec.integrators = read_integrators(system, spec.forceField.groups, spec.schedule);
    // The entries read here must use every key they hold (a parameter the component does not take
    // is refused as at load); the simulation steps are not read again.
    for (const input::ComponentEntry& entry : system.forceField) entry.node.check_all_used();
    for (const input::ComponentEntry& entry : system.integrators) entry.node.check_all_used();
    return spec;
}

}  // namespace structmd
