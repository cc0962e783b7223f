#include "parallel/replica_documents.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/error.hpp"
#include "core/registry.hpp"
#include "input/description.hpp"

namespace structmd {

namespace {

using json = nlohmann::json;

// The entry's key, written once: parallel tempering runs the input as replicas (load_over_ranks.cpp),
// so no engine's step registry holds it.
const ComponentKey& parallel_tempering() {
    static const ComponentKey key{"ReplicaExchange", "ParallelTempering"};
    return key;
}

const json* find(const json& node, std::initializer_list<const char*> path) {
    const json* at = &node;
    for (const char* key : path) {
        if (!at->is_object() || !at->contains(key)) return nullptr;
        at = &(*at)[key];
    }
    return at;
}

// The system's ["Simulation","Information"] entry, or nullptr (the reader then says it is missing).
json* information(json& document) {
    if (!document.contains("system") || !document["system"].is_object()) return nullptr;
    for (auto& [name, entry] : document["system"].items())
        if (entry.is_object() && entry.value("type", json()) == json::array({"Simulation", "Information"})) return &entry;
    return nullptr;
}

}  // namespace

bool asks_for_replicas(const input::SystemDescription& system) {
    return std::any_of(system.simulationSteps.begin(), system.simulationSteps.end(),
                       [](const input::ComponentEntry& entry) {
                           return ComponentKey{entry.cls, entry.subclass} == parallel_tempering();
                       });
}

ReplicaExchangeSpec take_replica_exchange(json& document) {
    json& steps = document.at("simulationStep");
    const json type = json::array({parallel_tempering().cls, parallel_tempering().subclass});
    std::optional<ReplicaExchangeSpec> found;
    for (auto it = steps.begin(); it != steps.end(); ++it) {
        const json& entry = it.value();
        if (!entry.is_object() || entry.value("type", json()) != type) continue;
        const std::string path = "simulationStep." + it.key();
        if (found) throw input_error(path, "a second ReplicaExchange entry (one ensemble has one set of temperatures)");
        ReplicaExchangeSpec spec;
        spec.name = it.key();
        const json* parameters = find(entry, {"parameters"});
        if (!parameters || !parameters->is_object()) throw input_error(path + ".parameters", "expected an object");
        for (auto p = parameters->begin(); p != parameters->end(); ++p)
            if (p.key() != "intervalStep" && p.key() != "temperatures" && p.key() != "outputFilePath")
                throw input_error(path + ".parameters." + p.key(),
                                  "unknown parameter (known: intervalStep, temperatures, outputFilePath)");
        const json* interval = find(*parameters, {"intervalStep"});
        if (!interval || !interval->is_number_integer() || interval->get<int64_t>() <= 0)
            throw input_error(path + ".parameters.intervalStep", "expected an integer > 0");
        spec.interval = interval->get<int64_t>();
        const json* temperatures = find(*parameters, {"temperatures"});
        if (!temperatures || !temperatures->is_array() || temperatures->size() < 2)
            throw input_error(path + ".parameters.temperatures", "expected a list of at least two temperatures");
        for (size_t k = 0; k < temperatures->size(); ++k) {
            const json& t = (*temperatures)[k];
            if (!t.is_number() || !(t.get<double>() > 0.0) || !std::isfinite(t.get<double>()))
                throw input_error(path + ".parameters.temperatures[" + std::to_string(k) + "]",
                                  "expected a temperature > 0, got " + t.dump());
            spec.temperatures.push_back(t.get<double>());
        }
        const json* output = find(*parameters, {"outputFilePath"});
        if (!output || !output->is_string()) throw input_error(path + ".parameters.outputFilePath", "expected a path");
        spec.outputPath = output->get<std::string>();
        found = spec;
    }
    if (!found) throw Error(STRUCTMD_ERR_INTERNAL, "simulationStep: no parallel tempering entry to take");
    steps.erase(found->name);

    if (const json* integrators = find(document, {"integrator"}); integrators && integrators->is_object())
        for (auto it = integrators->begin(); it != integrators->end(); ++it)
            if (const json* t = find(it.value(), {"parameters", "temperature"}))
                throw Error(STRUCTMD_ERR_UNSUPPORTED, "integrator." + it.key() + ".parameters.temperature: under "
                            "parallel tempering the replicas' temperatures come from simulationStep." + found->name +
                            ".parameters.temperatures, in place of the ensemble's (drop this one); got " + t->dump());
    const json* ensemble = find(document, {"global", "ensemble"});
    if (!ensemble || !ensemble->contains("labels") || !ensemble->contains("data"))
        throw input_error("global.ensemble", "parallel tempering needs the ensemble whose temperature it sets");
    const json* info = information(document);
    const json* seed = info ? find(*info, {"parameters", "seed"}) : nullptr;
    found->seed = seed && seed->is_number_unsigned() ? seed->get<uint64_t>() : input::kDefaultSeed;
    return *found;
}

json replica_document(const json& document, const ReplicaExchangeSpec& spec, int k) {
    json replica = document;
    // An ensemble of another shape is left as it is, for the replica's reader to name.
    json* global = replica.is_object() && replica.contains("global") && replica["global"].is_object() ? &replica["global"]
                                                                                                     : nullptr;
    json* ensemble = global && global->contains("ensemble") && (*global)["ensemble"].is_object() ? &(*global)["ensemble"]
                                                                                                 : nullptr;
    if (ensemble && ensemble->contains("labels") && (*ensemble)["labels"].is_array() && ensemble->contains("data") &&
        (*ensemble)["data"].is_array()) {
        const json& labels = (*ensemble)["labels"];
        for (size_t c = 0; c < labels.size(); ++c)
            if (labels[c] == "temperature")
                for (json& row : (*ensemble)["data"])
                    if (row.is_array() && c < row.size()) row[c] = spec.temperatures[static_cast<size_t>(k)];
    }
    // Replica k's noise: the seed moved along by a large odd constant (Weyl sequence), so no two
    // replicas draw alike.
    if (json* info = information(replica); info && info->contains("parameters") && (*info)["parameters"].is_object())
        (*info)["parameters"]["seed"] = spec.seed + static_cast<uint64_t>(k) * 0x9E3779B97F4A7C15ull;
    if (replica.contains("simulationStep") && replica["simulationStep"].is_object())
        for (auto& [name, entry] : replica["simulationStep"].items()) {
            if (!entry.is_object() || !entry.contains("parameters") || !entry["parameters"].is_object()) continue;
            json& parameters = entry["parameters"];
            if (!parameters.contains("outputFilePath") || !parameters["outputFilePath"].is_string()) continue;
            const std::string path = parameters["outputFilePath"].get<std::string>();
            const size_t slash = path.find_last_of('/');
            const size_t cut = slash == std::string::npos ? 0 : slash + 1;
            parameters["outputFilePath"] =
                path.substr(0, cut) + "temperature" + std::to_string(k) + "_" + path.substr(cut);
        }
    return replica;
}

}  // namespace structmd
