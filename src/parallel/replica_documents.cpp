#include "parallel/replica_documents.hpp"

#include <optional>

#include "core/error.hpp"
#include "input/read_parameters.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

namespace {

using json = nlohmann::json;

// The system's ["Simulation","Information"] entry, or nullptr (the reader then says it is missing).
json* information(json& document) {
    if (!document.contains("system") || !document["system"].is_object()) return nullptr;
    for (auto& [name, entry] : document["system"].items())
        if (entry.is_object() && entry.value("type", json()) == json::array({"Simulation", "Information"})) return &entry;
    return nullptr;
}

}  // namespace

const input::ComponentEntry* replica_exchange_entry(const input::SystemDescription& system) {
    const input::ComponentEntry* found = nullptr;
    for (const input::ComponentEntry& entry : system.simulationSteps) {
        const SimulationStepEntry* step = simulation_step_registry().find({entry.cls, entry.subclass});
        if (!step || !step->runsReplicas) continue;
        if (found)
            throw input_error(entry.node.path(),
                              "a second ReplicaExchange entry (one ensemble has one set of temperatures)");
        found = &entry;
    }
    return found;
}

ReplicaExchangeSpec read_replica_exchange(const input::ParsedDocument& document, const input::ComponentEntry& entry) {
    const SimulationStepEntry& step =
        simulation_step_registry().at({entry.cls, entry.subclass}, entry.node.path() + ".type", "simulation step");
    const StepParameters parameters(entry.node, step.parameters);
    // Its parameters are read here only: the replicas run the input without the entry.
    entry.node.check_all_used();
    if (parameters.text("group") != "All")
        throw Error(STRUCTMD_ERR_UNSUPPORTED, parameters.path("group") +
                                                  ": the replicas exchange whole configurations; a group other than "
                                                  "\"All\" is not supported");
    ReplicaExchangeSpec spec;
    spec.name = entry.name;
    spec.interval = parameters.integer("intervalStep");
    spec.start = parameters.integer("startStep");
    spec.end = parameters.integer("endStep");
    spec.temperatures = parameters.numbers("temperatures");
    if (spec.temperatures.size() < 2)
        throw input_error(parameters.path("temperatures"), "expected a list of at least two temperatures");
    for (size_t k = 0; k < spec.temperatures.size(); ++k)
        if (!(spec.temperatures[k] > 0.0))
            throw input_error(parameters.path("temperatures") + "[" + std::to_string(k) + "]",
                              "expected a temperature > 0, got " + json(spec.temperatures[k]).dump());
    spec.outputPath = parameters.text("outputFilePath");

    for (const input::ComponentEntry& integrator : document.system.integrators) {
        const input::TrackedNode own = input::parameters_of(integrator.node);
        if (const auto t = own.valid() ? own.find("temperature") : std::nullopt)
            throw Error(STRUCTMD_ERR_UNSUPPORTED, t->path() + ": under parallel tempering the replicas' temperatures "
                        "come from " + parameters.path("temperatures") + ", in place of the ensemble's (drop this "
                        "one); got " + t->json().dump());
    }
    const json& whole = document.root.json();
    const bool ensemble = whole.contains("global") && whole["global"].contains("ensemble") &&
                          whole["global"]["ensemble"].contains("labels") && whole["global"]["ensemble"].contains("data");
    if (!ensemble) throw input_error("global.ensemble", "parallel tempering needs the ensemble whose temperature it sets");
    spec.seed = document.system.seed;
    return spec;
}

json replica_document(const json& document, const ReplicaExchangeSpec& spec, int k) {
    json replica = document;
    replica["simulationStep"].erase(spec.name);
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
