#include "parallel/domain_document.hpp"

#include <algorithm>
#include <set>
#include <unordered_map>

#include "core/error.hpp"

namespace structmd {

namespace {

using json = nlohmann::json;

Error unsupported(const std::string& path, const std::string& what) {
    return Error(STRUCTMD_ERR_UNSUPPORTED, path + ": " + what + " is not available under domain decomposition");
}

int column(const json& labels, const std::string& name) {
    for (size_t k = 0; k < labels.size(); ++k)
        if (labels[k].is_string() && labels[k].get<std::string>() == name) return static_cast<int>(k);
    return -1;
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

int64_t id_at(const json& row, int col, const std::string& path) {
    if (!row.is_array() || col >= static_cast<int>(row.size()) || !row[col].is_number_integer())
        throw input_error(path, "expected a row with an integer id");
    return row[col].get<int64_t>();
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

DomainDocument::DomainDocument(json document) {
    check_sections(document);
    json& topology = document["topology"];
    if (!topology.contains("structure")) throw input_error("topology.structure", "expected a table with labels and data");
    const json& labels = labels_of(topology["structure"], "topology.structure");
    only_labels(labels, {"id", "type", "batchId", "modelId", "resId", "chainId"}, "topology.structure");
    structureIdColumn_ = column(labels, "id");
    if (structureIdColumn_ < 0) throw input_error("topology.structure.labels", "expected an 'id' column");
    structure_ = std::move(topology["structure"]["data"]);
    topology["structure"]["data"] = json::array();
    structureRow_.assign(structure_.size(), structure_.size());
    for (size_t r = 0; r < structure_.size(); ++r) {
        const std::string path = "topology.structure.data[" + std::to_string(r) + "]";
        const int64_t id = id_at(structure_[r], structureIdColumn_, path);
        if (id < 0 || id >= static_cast<int64_t>(structure_.size()) || structureRow_[static_cast<size_t>(id)] != structure_.size())
            throw input_error(path, "expected the ids 0 to " + std::to_string(structure_.size() - 1) + ", each once");
        structureRow_[static_cast<size_t>(id)] = r;
    }
    bondsOf_.resize(structure_.size());
    partners_.resize(structure_.size());
    if (topology.contains("forceField"))
        for (auto it = topology["forceField"].begin(); it != topology["forceField"].end(); ++it) {
            const std::string path = "topology.forceField." + it.key();
            json& entry = it.value();
            if (has_type(entry, "VerletConditionalListSet")) continue;
            if (has_type(entry, "NonBonded") && kPairTerms.count(entry["type"][1].get<std::string>())) continue;
            if (!has_type(entry, "Bond2")) throw unsupported(path, "forceField entry " + type_text(entry));
            const json& bondLabels = labels_of(entry, path);
            BondTable table{it.key(), column(bondLabels, "id_i"), column(bondLabels, "id_j")};
            if (table.columnI < 0 || table.columnJ < 0) throw input_error(path + ".labels", "expected id_i and id_j");
            const int index = static_cast<int>(bondTables_.size());
            bondRows_.push_back(std::move(entry["data"]));
            entry["data"] = json::array();
            const json& rows = bondRows_.back();
            for (size_t r = 0; r < rows.size(); ++r) {
                const std::string rowPath = path + ".data[" + std::to_string(r) + "]";
                const int64_t i = id_at(rows[r], table.columnI, rowPath), j = id_at(rows[r], table.columnJ, rowPath);
                for (int64_t id : {i, j})
                    if (id < 0 || id >= particle_count())
                        throw input_error(rowPath, "no particle has id " + std::to_string(id));
                bondsOf_[static_cast<size_t>(i)].emplace_back(index, r);
                if (j != i) bondsOf_[static_cast<size_t>(j)].emplace_back(index, r);
                partners_[static_cast<size_t>(i)].push_back(j);
                partners_[static_cast<size_t>(j)].push_back(i);
            }
            bondTables_.push_back(table);
        }
    document.erase("simulationStep");
    document["state"] = {{"labels", {"id", "position", "velocity"}}, {"data", json::array()}};
    skeleton_ = std::move(document);
}

std::string DomainDocument::local_text(const std::vector<int64_t>& ids, int64_t owned, const std::vector<double>& positions,
                                       const std::vector<double>& velocities, int64_t step, double time,
                                       int64_t remaining) const {
    json document = skeleton_;
    std::unordered_map<int64_t, int64_t> slotOf;
    slotOf.reserve(ids.size());
    for (size_t slot = 0; slot < ids.size(); ++slot) slotOf[ids[slot]] = static_cast<int64_t>(slot);

    json& structure = document["topology"]["structure"]["data"];
    json& state = document["state"]["data"];
    for (size_t slot = 0; slot < ids.size(); ++slot) {
        json row = structure_[structureRow_[static_cast<size_t>(ids[slot])]];
        row[structureIdColumn_] = slot;
        structure.push_back(std::move(row));
        const double* x = &positions[3 * slot];
        const double* v = &velocities[3 * slot];
        state.push_back(json::array({slot, {x[0], x[1], x[2]}, {v[0], v[1], v[2]}}));
    }
    // A bond is kept once when the domain owns one of its particles; its other particle is then a
    // ghost or owned (the view checks that beforehand).
    std::vector<std::vector<size_t>> kept(bondTables_.size());
    for (int64_t slot = 0; slot < owned; ++slot)
        for (const auto& [table, row] : bondsOf_[static_cast<size_t>(ids[static_cast<size_t>(slot)])])
            kept[static_cast<size_t>(table)].push_back(row);
    for (size_t t = 0; t < bondTables_.size(); ++t) {
        std::sort(kept[t].begin(), kept[t].end());
        kept[t].erase(std::unique(kept[t].begin(), kept[t].end()), kept[t].end());
        json& data = document["topology"]["forceField"][bondTables_[t].name]["data"];
        for (size_t r : kept[t]) {
            json row = bondRows_[t][r];
            for (int col : {bondTables_[t].columnI, bondTables_[t].columnJ})
                row[col] = slotOf.at(row[col].get<int64_t>());
            data.push_back(std::move(row));
        }
    }
    // The clock goes on from where the previous engine of the domain left it.
    json* fundamental = nullptr;
    if (document.contains("global"))
        for (auto it = document["global"].begin(); it != document["global"].end(); ++it)
            if (has_type(it.value(), "Fundamental")) fundamental = &it.value();
    if (!fundamental) {
        document["global"]["fundamental"] = {{"type", {"Fundamental", "Time"}}};
        fundamental = &document["global"]["fundamental"];
    }
    (*fundamental)["parameters"]["currentStep"] = step;
    (*fundamental)["parameters"]["simulationTime"] = time;
    // The schedule (one integrator, check_sections) ends where the whole system's does.
    if (document.contains("integrator"))
        for (auto it = document["integrator"].begin(); it != document["integrator"].end(); ++it) {
            json& entry = it.value();
            if (!has_type(entry, "Schedule") || !entry.contains("labels") || !entry.contains("data")) continue;
            const int steps = column(entry["labels"], "steps");
            if (steps >= 0 && entry["data"].is_array() && entry["data"].size() == 1 && entry["data"][0].is_array() &&
                steps < static_cast<int>(entry["data"][0].size()))
                entry["data"][0][steps] = remaining;
        }
    return document.dump();
}

}  // namespace structmd
