#include "simulation/transverser_call.hpp"

#include <cmath>
#include <memory>

#include <nlohmann/json.hpp>

#include "forcefield/component_set.hpp"
#include "input/read_parameters.hpp"
#include "input/tracked_node.hpp"

namespace structmd {

TransverserCall make_transverser_call(const ForceFieldComponents& components, const std::string& name,
                                      const char* parameters, double cutoff) {
    auto [source, entry] = components.transverser(name);
    auto state = std::make_shared<input::TrackingState>();
    nlohmann::json& doc = state->document;
    doc = nlohmann::json::object();
    if (parameters && *parameters) {
        try {
            doc["parameters"] = nlohmann::json::parse(parameters);
        } catch (const nlohmann::json::exception& e) {
            throw Error(STRUCTMD_ERR_ARGUMENT, std::string("parameters: not valid JSON: ") + e.what());
        }
        if (!doc["parameters"].is_object()) throw Error(STRUCTMD_ERR_ARGUMENT, "parameters: expected a JSON object");
    }
    const input::TrackedNode root(state, &doc, name);
    TransverserCall call;
    call.name = name;
    call.values = entry->values;
    call.parameters = input::read_parameters(root, entry->parameters);
    const input::TrackedNode given = input::parameters_of(root);
    if (given.valid()) {
        if (auto group = given.find("group")) {
            call.group = group->as<std::string>();
            call.path = group->path();
        }
        given.check_all_used();
    }
    if (!(cutoff >= 0) || !std::isfinite(cutoff))
        throw input_error("cutoff", "expected a finite number >= 0 (0: all pairs), got " + std::to_string(cutoff));
    call.cutoff = cutoff;
    call.source = std::move(source);
    return call;
}

int transverser_values(const ForceFieldComponents& components, const std::string& name) {
    return components.transverser(name).second->values;
}

}  // namespace structmd
