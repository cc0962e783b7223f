#include "parallel/domain_support.hpp"

#include <algorithm>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/box.hpp"
#include "core/error.hpp"
#include "input/read_parameters.hpp"
#include "integrators/integrator_spec.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

namespace {

using input::ComponentEntry;
using input::TrackedNode;

// Something the domains do not run: the JSON path that asks for it, and what it is. The checks list
// them in document order and load_over_ranks is refused with the first.
struct Refusal {
    std::string path;
    std::string what;
};
using Refusals = std::vector<Refusal>;

// As the input writes it: ["Class","SubClass"].
std::string type_text(const ComponentKey& key) { return "[\"" + key.cls + "\",\"" + key.subclass + "\"]"; }
ComponentKey key_of(const ComponentEntry& entry) { return {entry.cls, entry.subclass}; }

// What the domains carry of the document's layout: the keys an object may have, or the labels a
// table may have. The reader has refused any global entry other than units, types, ensemble and
// fundamental. Each domain moves positions and velocities by id; the structure's columns are read
// once for the whole system.
enum class Part { sections, columns };
struct Layout {
    std::vector<std::string> path;  // from the root
    Part part;
    std::set<std::string> allowed;
};
const std::vector<Layout>& layout() {
    static const std::vector<Layout> rules = {
        {{}, Part::sections, {"system", "global", "integrator", "state", "topology", "simulationStep"}},
        {{"topology"}, Part::sections, {"structure", "forceField"}},
        {{"state"}, Part::columns, {"id", "position", "velocity"}},
        {{"topology", "structure"}, Part::columns, {"id", "type", "batchId", "modelId", "resId", "chainId"}},
    };
    return rules;
}

void refuse_layout(const TrackedNode& root, Refusals& found) {
    for (const Layout& rule : layout()) {
        std::optional<TrackedNode> node = root;
        for (const std::string& key : rule.path)
            if (node) node = node->find(key);
        if (!node) continue;
        if (rule.part == Part::sections) {
            for (const std::string& key : node->keys()) {
                const std::string path = node->path().empty() ? key : node->path() + "." + key;
                if (!rule.allowed.count(key)) found.push_back({path, "the section '" + path + "'"});
            }
            continue;
        }
        const TrackedNode labels = node->at("labels");
        for (size_t k = 0; k < labels.size(); ++k) {
            const std::string label = labels.at(k).as<std::string>();
            if (!rule.allowed.count(label)) found.push_back({labels.path(), "column \"" + label + "\""});
        }
    }
    // Of the system section, the domains read the simulation's information only.
    if (const auto system = root.find("system"))
        for (const std::string& key : system->keys()) {
            const TrackedNode type = system->at(key).at("type");
            const ComponentKey entry{type.at(0).as<std::string>(), type.at(1).as<std::string>()};
            if (!(entry == ComponentKey{"Simulation", "Information"}))
                found.push_back({system->path() + "." + key, "entry " + type_text(entry)});
        }
}

// One integrator, simulation step or force-field entry, as its registry declares it.
struct Declared {
    const char* kind;  // "integrator", "simulation step", "forceField entry"
    std::string path;
    ComponentKey key;
    bool underDomains;  // false too for a key its registry lacks
    // "an integrator of a group" when it acts on a group rather than every particle, which a domain
    // would have to select among its own particles and ghosts.
    const char* ofGroup = nullptr;
};

void refuse(const Declared& component, Refusals& found) {
    if (!component.underDomains)
        found.push_back({component.path, std::string(component.kind) + " " + type_text(component.key)});
    if (component.ofGroup) found.push_back({component.path + ".parameters.group", component.ofGroup});
}

bool of_group(const TrackedNode& entry) {
    const TrackedNode parameters = input::parameters_of(entry);
    return parameters.valid() && parameters.get_or<std::string>("group", "All") != "All";
}

void refuse_components(const input::SystemDescription& system, const SimulationSpec& spec,
                       const Registry<ForceFieldComponent>& components, Refusals& found) {
    if (system.schedule.size() > 1) found.push_back({system.schedulePath, "a schedule of more than one integrator"});
    // Slabs cut the box's longest axis into periodic pieces; an open axis has no length to cut.
    if (has_open_axis(system.box[0], system.box[1], system.box[2]))
        found.push_back({system.boxPath, "a box with an open axis (a length of 0 or \"inf\")"});
    for (const IntegratorSpec& integrator : spec.integrators) {
        const IntegratorComponent* component = integrator_registry().find(integrator.key);
        refuse({"integrator", integrator.path, integrator.key, component && component->underDomains,
                integrator.group != -1 ? "an integrator of a group" : nullptr},
               found);
        if (const char* name = component ? component->wholeSystemParameter : nullptr;
            name && integrator.parameters[name] != 0.0)
            found.push_back({integrator.path + ".parameters." + name, component->wholeSystemEffect});
    }
    for (const ComponentEntry& entry : system.simulationSteps) {
        const SimulationStepEntry* step = simulation_step_registry().find(key_of(entry));
        refuse({"simulation step", entry.node.path(), key_of(entry), step && step->underDomains,
                of_group(entry.node) ? "a simulation step of a group" : nullptr},
               found);
    }
    // Groups named in the integrator and simulationStep sections select particles by id.
    for (const ComponentEntry& entry : system.sectionGroups)
        found.push_back({entry.node.path(), "entry " + type_text(key_of(entry))});
    for (const ComponentEntry& entry : system.forceField) {
        // Each domain's engine builds its own lists over the particles it holds, ghosts included.
        const auto list = std::find_if(spec.forceField.lists.begin(), spec.forceField.lists.end(),
                                       [&](const NeighbourListSpec& l) { return l.path == entry.node.path(); });
        // A domain's pairs are its particles' within a ghost width, not all pairs.
        if (list != spec.forceField.lists.end() && list->allPairs)
            found.push_back({entry.node.path(), "entry " + type_text(key_of(entry))});
        if (list != spec.forceField.lists.end()) continue;
        const ForceFieldComponent* component = components.find(key_of(entry));
        refuse({"forceField entry", entry.node.path(), key_of(entry), component && component->underDomains}, found);
    }
}

}  // namespace

void check_domain_support(const input::ParsedDocument& document, const SimulationSpec& spec,
                          const Registry<ForceFieldComponent>& components) {
    Refusals found;
    refuse_layout(document.root, found);
    refuse_components(document.system, spec, components, found);
    if (!found.empty())
        throw Error(STRUCTMD_ERR_UNSUPPORTED,
                    found.front().path + ": " + found.front().what + " is not available under domain decomposition");
}

}  // namespace structmd
