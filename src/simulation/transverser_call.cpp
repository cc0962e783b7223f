#include "simulation/transverser_call.hpp"

#include <cmath>
#include <memory>

#include <nlohmann/json.hpp>

#include "forcefield/component_set.hpp"
#include "input/read_parameters.hpp"
#include "input/tracked_node.hpp"

namespace structmd {

TransverserCall make_transverser_call(const ForceFieldComponents& components, const std::string& name,
                                      const input::TrackedNode& parameters, const std::string& path, double cutoff) {
    auto [source, entry] = components.transverser(name);
    TransverserCall call;
    call.name = name;
    call.values = entry->values;
    call.parameters = input::read_parameter_object(parameters, path, entry->parameters);
    if (parameters.valid()) parameters.check_all_used();
    call.cutoff = cutoff;
    call.source = std::move(source);
    return call;
}

TransverserCall make_transverser_call(const ForceFieldComponents& components, const std::string& name,
                                      const char* parameters, double cutoff) {
    components.transverser(name);  // an unknown name before anything about its parameters
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
    const input::TrackedNode given = input::parameters_of(root);
    std::string group = "All", groupPath;
    if (given.valid())
        if (auto node = given.find("group")) {
            group = node->as<std::string>();
            groupPath = node->path();
        }
    if (!(cutoff >= 0) || !std::isfinite(cutoff))
        throw input_error("cutoff", "expected a finite number >= 0 (0: all pairs), got " + std::to_string(cutoff));
    TransverserCall call = make_transverser_call(components, name, given, root.path() + ".parameters", cutoff);
    call.group = std::move(group);
    call.path = std::move(groupPath);
    return call;
}

int transverser_values(const ForceFieldComponents& components, const std::string& name) {
    return components.transverser(name).second->values;
}

}  // namespace structmd
