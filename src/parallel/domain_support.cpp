#include "parallel/domain_support.hpp"

#include <set>
#include <string>

#include "core/error.hpp"

namespace structmd {

namespace {

using json = nlohmann::json;

Error unsupported(const std::string& path, const std::string& what) {
    return Error(STRUCTMD_ERR_UNSUPPORTED, path + ": " + what + " is not available under domain decomposition");
}

std::string type_text(const json& entry) { return entry.contains("type") ? entry["type"].dump() : "(no type)"; }

bool has_type(const json& entry, const std::string& cls, const std::string& sub = std::string()) {
    if (!entry.is_object() || !entry.contains("type") || !entry["type"].is_array() || entry["type"].size() != 2) return false;
    const json& type = entry["type"];
    return type[0] == cls && (sub.empty() || type[1] == sub);
}

const json& labels_of(const json& table, const std::string& path) {
    if (!table.is_object() || !table.contains("labels") || !table["labels"].is_array() || !table.contains("data") ||
        !table["data"].is_array())
        throw input_error(path, "expected a table with labels and data");
    return table["labels"];
}

void only_labels(const json& labels, const std::set<std::string>& allowed, const std::string& path) {
    for (const json& label : labels)
        if (!label.is_string() || !allowed.count(label.get<std::string>()))
            throw unsupported(path + ".labels", "column " + label.dump());
}

// The pair terms over a neighbour list whose functors read nothing a domain's engine lacks.
const std::set<std::string> kPairTerms = {
    "LennardJonesType1", "LennardJonesType2", "LennardJonesType3", "WCAType1", "WCAType2", "WCAType3",
    "GeneralLennardJonesType1", "GeneralLennardJonesType2", "GeneralLennardJonesType3", "Steric6", "Steric12",
    "SplitLennardJones", "DebyeHuckel"};

void check_sections(const json& document) {
    if (!document.is_object()) throw input_error("", "expected a JSON object");
    for (auto it = document.begin(); it != document.end(); ++it) {
        const std::string& key = it.key();
        if (key != "system" && key != "global" && key != "integrator" && key != "state" && key != "topology" &&
            key != "simulationStep")
            throw unsupported(key, "the section '" + key + "'");
    }
    if (document.contains("system"))
        for (auto it = document["system"].begin(); it != document["system"].end(); ++it)
            if (!has_type(it.value(), "Simulation", "Information"))
                throw unsupported("system." + it.key(), "entry " + type_text(it.value()));
    if (document.contains("global"))
        for (auto it = document["global"].begin(); it != document["global"].end(); ++it) {
            const json& entry = it.value();
            if (!(has_type(entry, "Units") || has_type(entry, "Types") || has_type(entry, "Fundamental") ||
                  has_type(entry, "Ensemble")))
                throw unsupported("global." + it.key(), "entry " + type_text(entry));
        }
    if (document.contains("integrator"))
        for (auto it = document["integrator"].begin(); it != document["integrator"].end(); ++it) {
            const std::string path = "integrator." + it.key();
            const json& entry = it.value();
            if (has_type(entry, "Schedule")) {
                if (entry.contains("data") && entry["data"].is_array() && entry["data"].size() > 1)
                    throw unsupported(path, "a schedule of more than one integrator");
                continue;
            }
            if (!has_type(entry, "Verlet", "VelocityVerlet") && !has_type(entry, "Langevin", "BBK"))
                throw unsupported(path, "integrator " + type_text(entry));
            const json parameters = entry.value("parameters", json::object());
            if (parameters.contains("group") && parameters["group"] != "All")
                throw unsupported(path + ".parameters.group", "an integrator of a group");
            if (parameters.contains("stopTransRotSteps") && parameters["stopTransRotSteps"] != 0)
                throw unsupported(path + ".parameters.stopTransRotSteps", "removing the whole system's motion");
        }
    if (document.contains("simulationStep"))
        for (auto it = document["simulationStep"].begin(); it != document["simulationStep"].end(); ++it) {
            const std::string path = "simulationStep." + it.key();
            if (!has_type(it.value(), "WriteStep", "WriteStep"))
                throw unsupported(path, "simulation step " + type_text(it.value()));
            const json parameters = it.value().value("parameters", json::object());
            if (parameters.contains("group") && parameters["group"] != "All")
                throw unsupported(path + ".parameters.group", "a simulation step of a group");
        }
    if (!document.contains("topology") || !document["topology"].is_object())
        throw input_error("topology", "expected an object with a structure");
    for (auto it = document["topology"].begin(); it != document["topology"].end(); ++it)
        if (it.key() != "structure" && it.key() != "forceField")
            throw unsupported("topology." + it.key(), "the section 'topology." + it.key() + "'");
    if (document.contains("state")) {
        only_labels(labels_of(document["state"], "state"), {"id", "position", "velocity"}, "state");
    }
}

}  // namespace

void check_domain_support(const json& document) {
    check_sections(document);
    const json& topology = document["topology"];
    if (!topology.contains("structure")) throw input_error("topology.structure", "expected a table with labels and data");
    only_labels(labels_of(topology["structure"], "topology.structure"),
                {"id", "type", "batchId", "modelId", "resId", "chainId"}, "topology.structure");
    if (!topology.contains("forceField")) return;
    const json& forceField = topology["forceField"];
    for (auto it = forceField.begin(); it != forceField.end(); ++it) {
        const json& entry = it.value();
        if (has_type(entry, "VerletConditionalListSet") || has_type(entry, "Bond2")) continue;
        if (has_type(entry, "NonBonded") && kPairTerms.count(entry["type"][1].get<std::string>())) continue;
        throw unsupported("topology.forceField." + it.key(), "forceField entry " + type_text(entry));
    }
}

}  // namespace structmd
