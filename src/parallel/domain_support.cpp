#include "parallel/domain_support.hpp"

#include <algorithm>
#include <set>
#include <string>

#include "core/error.hpp"
#include "input/read_parameters.hpp"
#include "integrators/integrator_spec.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

namespace {

using input::ComponentEntry;
using input::TrackedNode;

Error unsupported(const std::string& path, const std::string& what) {
    return Error(STRUCTMD_ERR_UNSUPPORTED, path + ": " + what + " is not available under domain decomposition");
}

// As the input writes it: ["Class","SubClass"].
std::string type_text(const std::string& cls, const std::string& subclass) {
    return "[\"" + cls + "\",\"" + subclass + "\"]";
}
std::string type_text(const ComponentEntry& entry) { return type_text(entry.cls, entry.subclass); }

// The labels of a table the reader has already checked.
void only_labels(const TrackedNode& table, const std::set<std::string>& allowed) {
    const TrackedNode labels = table.at("labels");
    for (size_t k = 0; k < labels.size(); ++k) {
        const std::string label = labels.at(k).as<std::string>();
        if (!allowed.count(label)) throw unsupported(labels.path(), "column \"" + label + "\"");
    }
}

// The document's layout: its sections, the system's entries and the particles' columns. The reader
// has refused any global entry other than units, types, ensemble and fundamental.
void check_layout(const TrackedNode& root) {
    for (const std::string& key : root.keys())
        if (key != "system" && key != "global" && key != "integrator" && key != "state" && key != "topology" &&
            key != "simulationStep")
            throw unsupported(key, "the section '" + key + "'");
    if (const auto system = root.find("system"))
        for (const std::string& key : system->keys()) {
            const TrackedNode type = system->at(key).at("type");
            const std::string cls = type.at(0).as<std::string>(), subclass = type.at(1).as<std::string>();
            if (cls != "Simulation" || subclass != "Information")
                throw unsupported(system->path() + "." + key, "entry " + type_text(cls, subclass));
        }
    const TrackedNode topology = root.at("topology");
    for (const std::string& key : topology.keys())
        if (key != "structure" && key != "forceField")
            throw unsupported(topology.path() + "." + key, "the section '" + topology.path() + "." + key + "'");
    if (const auto state = root.find("state")) only_labels(*state, {"id", "position", "velocity"});
    only_labels(topology.at("structure"), {"id", "type", "batchId", "modelId", "resId", "chainId"});
}

void check_integrators(const input::SystemDescription& system, const SimulationSpec& spec) {
    if (system.schedule.size() > 1) throw unsupported(system.schedulePath, "a schedule of more than one integrator");
    for (const IntegratorSpec& integrator : spec.integrators) {
        const IntegratorComponent* component = integrator_registry().find(integrator.key);
        if (!component || !component->underDomains)
            throw unsupported(integrator.path, "integrator " + type_text(integrator.key.cls, integrator.key.subclass));
        if (integrator.group != -1) throw unsupported(integrator.path + ".parameters.group", "an integrator of a group");
        if (const char* name = component->wholeSystemParameter; name && integrator.parameters[name] != 0.0)
            throw unsupported(integrator.path + ".parameters." + name, component->wholeSystemEffect);
    }
}

void check_steps(const input::SystemDescription& system) {
    for (const ComponentEntry& entry : system.simulationSteps) {
        const SimulationStepEntry* step = simulation_step_registry().find({entry.cls, entry.subclass});
        if (!step || !step->underDomains)
            throw unsupported(entry.node.path(), "simulation step " + type_text(entry));
        const TrackedNode parameters = input::parameters_of(entry.node);
        if (parameters.valid() && parameters.get_or<std::string>("group", "All") != "All")
            throw unsupported(entry.node.path() + ".parameters.group", "a simulation step of a group");
    }
    // Groups named in the integrator and simulationStep sections select particles by id.
    for (const ComponentEntry& entry : system.sectionGroups)
        throw unsupported(entry.node.path(), "entry " + type_text(entry));
}

void check_forcefield(const input::SystemDescription& system, const ForceFieldSpec& forceField,
                      const Registry<ForceFieldComponent>& components) {
    for (const ComponentEntry& entry : system.forceField) {
        const std::string& path = entry.node.path();
        // Each domain's engine builds its own lists over the particles it holds, ghosts included.
        const bool list = std::any_of(forceField.lists.begin(), forceField.lists.end(),
                                      [&](const NeighbourListSpec& l) { return l.path == path; });
        if (list) continue;
        const ForceFieldComponent* component = components.find({entry.cls, entry.subclass});
        if (!component || !component->underDomains) throw unsupported(path, "forceField entry " + type_text(entry));
    }
}

}  // namespace

void check_domain_support(const input::ParsedDocument& document, const SimulationSpec& spec,
                          const Registry<ForceFieldComponent>& components) {
    check_layout(document.root);
    check_integrators(document.system, spec);
    check_steps(document.system);
    check_forcefield(document.system, spec.forceField, components);
}

}  // namespace structmd
