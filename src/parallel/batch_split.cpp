#include "parallel/batch_split.hpp"

#include <algorithm>
#include <optional>

#include "core/error.hpp"

namespace structmd {

namespace {

using json = nlohmann::json;

// Something of the input that no share can take: the JSON path that asks for it, and what it is.
struct Refusal {
    std::string path;
    std::string what;
};

Error unsupported(const Refusal& refusal) {
    return Error(STRUCTMD_ERR_UNSUPPORTED, refusal.path + ": " + refusal.what + " (batches over MPI ranks)");
}

int column(const json& labels, const std::string& name) {
    for (size_t k = 0; k < labels.size(); ++k)
        if (labels[k].is_string() && labels[k].get<std::string>() == name) return static_cast<int>(k);
    return -1;
}

// What a table's column is to the split, by its label.
enum class Column {
    particle,        // "id" and the members of bonded entries ("id_i"...): kept with the ids shifted
    batch,           // "batchId": the rows of other ranks' batches are dropped
    other,           // kept as it is (modelId, resId and chainId number within the structure)
    namesParticles,  // any other id column ("idSet", "firstId"...), which the split cannot rewrite
};

Column column_of(const std::string& label) {
    if (label == "id" || (label.rfind("id_", 0) == 0 && label.size() == 4)) return Column::particle;
    if (label == "batchId") return Column::batch;
    if (label == "modelId" || label == "resId" || label == "chainId") return Column::other;
    const bool id = label.rfind("id", 0) == 0 || (label.size() > 2 && label.compare(label.size() - 2, 2, "Id") == 0);
    return id ? Column::namesParticles : Column::other;
}

// The selection types of ["Groups","GroupsList"] that list particle ids.
bool selects_ids(const json& type) {
    return type.is_string() && (type == "Ids" || type == "notIds");
}

// What of the object at `path` names particles by id where the split cannot rewrite them for a share:
// a group of ids, an id column no share renumbers, and in a simulation step (which sees the whole
// system, batches_over_ranks.hpp, so reads nothing that depends on the share) a group other than
// "All" or a table of particles.
std::optional<Refusal> names_particles_by_id(const json& node, const std::string& path, bool step) {
    if (step && node.contains("parameters") && node["parameters"].is_object()) {
        const json& parameters = node["parameters"];
        if (parameters.contains("group") && parameters["group"] != "All")
            return Refusal{path + ".parameters.group", "a simulation step of a group other than \"All\""};
    }
    if (!node.contains("labels") || !node["labels"].is_array()) return std::nullopt;
    const bool data = node.contains("data") && node["data"].is_array();
    if (!step && !data) return std::nullopt;  // not a table
    const json& labels = node["labels"];
    for (const json& label : labels) {
        if (!label.is_string()) continue;
        const Column kind = column_of(label.get<std::string>());
        if (step && (kind == Column::particle || kind == Column::namesParticles))
            return Refusal{path + ".labels", "a simulation step with a table of particles"};
        if (kind == Column::namesParticles)
            return Refusal{path + ".labels", "column '" + label.get<std::string>() + "' names particles by id"};
    }
    const int typeColumn = column(labels, "type"), selection = column(labels, "selection");
    if (selection < 0 || typeColumn < 0 || !data) return std::nullopt;
    const json& rows = node["data"];
    for (size_t r = 0; r < rows.size(); ++r)
        if (rows[r].is_array() && typeColumn < static_cast<int>(rows[r].size()) && selects_ids(rows[r][typeColumn]))
            return Refusal{path + ".data[" + std::to_string(r) + "]", "a group selected by particle ids"};
    return std::nullopt;
}

struct Range {
    int64_t first = 0;
    int64_t end = 0;  // one past the last
    bool holds(int64_t id) const { return id >= first && id < end; }
};

int64_t id_at(const json& row, int col, const std::string& path) {
    if (!row.is_array() || col >= static_cast<int>(row.size()) || !row[col].is_number_integer())
        throw input_error(path, "expected a row with an integer id");
    return row[col].get<int64_t>();
}

class Splitter {
public:
    Splitter(Range range, std::vector<int> batches) : range_(range), batches_(std::move(batches)) {}

    void walk(json& node, const std::string& path) {
        if (node.is_array()) {
            for (size_t k = 0; k < node.size(); ++k) walk(node[k], path + "[" + std::to_string(k) + "]");
            return;
        }
        if (!node.is_object()) return;
        const bool step = path.rfind("simulationStep.", 0) == 0;
        if (const std::optional<Refusal> refusal = names_particles_by_id(node, path, step)) throw unsupported(*refusal);
        // A step's table stays whole.
        if (step && node.contains("labels")) return;
        if (node.contains("labels") && node.contains("data") && node["labels"].is_array() && node["data"].is_array()) {
            table(node, path);
            return;
        }
        for (auto it = node.begin(); it != node.end(); ++it) walk(it.value(), path.empty() ? it.key() : path + "." + it.key());
    }

private:
    // One labelled table: rows of particles or bonds kept with shifted ids, batched rows kept for this
    // rank's batches.
    void table(json& node, const std::string& path) {
        const json& labels = node["labels"];
        json& data = node["data"];
        std::vector<int> idColumns;
        int batchColumn = -1;
        for (size_t k = 0; k < labels.size(); ++k) {
            const Column kind = labels[k].is_string() ? column_of(labels[k].get<std::string>()) : Column::other;
            if (kind == Column::particle) idColumns.push_back(static_cast<int>(k));
            if (kind == Column::batch) batchColumn = static_cast<int>(k);
        }
        json kept = json::array();
        for (size_t r = 0; r < data.size(); ++r) {
            const std::string rowPath = path + ".data[" + std::to_string(r) + "]";
            json row = data[r];
            if (!idColumns.empty()) {
                int inside = 0;
                for (int col : idColumns) inside += range_.holds(id_at(row, col, rowPath)) ? 1 : 0;
                if (inside == 0) continue;
                if (inside != static_cast<int>(idColumns.size()))
                    throw unsupported({rowPath, "an entry between particles of batches on different ranks"});
                for (int col : idColumns) row[col] = row[col].get<int64_t>() - range_.first;
            } else if (batchColumn >= 0) {
                if (!row.is_array() || batchColumn >= static_cast<int>(row.size()) || !row[batchColumn].is_number_integer())
                    throw input_error(rowPath, "expected a row with an integer batchId");
                const int batch = row[batchColumn].get<int>();
                if (!std::binary_search(batches_.begin(), batches_.end(), batch)) continue;
            }
            kept.push_back(std::move(row));
        }
        data = std::move(kept);
    }

    Range range_;
    std::vector<int> batches_;
};

}  // namespace

BatchShare split_batches(const json& document, int rank, int ranks) {
    const json* structure = nullptr;
    if (document.is_object() && document.contains("topology") && document["topology"].is_object() &&
        document["topology"].contains("structure"))
        structure = &document["topology"]["structure"];
    if (!structure || !structure->is_object() || !structure->contains("labels") || !structure->contains("data"))
        throw input_error("topology.structure", "expected a table with labels and data");
    const json& labels = (*structure)["labels"];
    const json& data = (*structure)["data"];
    const int idColumn = column(labels, "id"), batchColumn = column(labels, "batchId");
    if (idColumn < 0) throw input_error("topology.structure.labels", "expected an 'id' column");

    // The batch of each id, which must run through the ids in increasing, contiguous blocks.
    std::vector<std::pair<int64_t, int>> byId;
    for (size_t r = 0; r < data.size(); ++r) {
        const std::string path = "topology.structure.data[" + std::to_string(r) + "]";
        const int64_t id = id_at(data[r], idColumn, path);
        int batch = 0;
        if (batchColumn >= 0) {
            if (batchColumn >= static_cast<int>(data[r].size()) || !data[r][batchColumn].is_number_integer())
                throw input_error(path, "expected an integer batchId");
            batch = data[r][batchColumn].get<int>();
        }
        byId.emplace_back(id, batch);
    }
    std::sort(byId.begin(), byId.end());
    std::vector<int> batchOrder;  // batchId values in id order, one entry per batch
    std::vector<int64_t> batchStart;
    for (size_t k = 0; k < byId.size(); ++k) {
        if (byId[k].first != static_cast<int64_t>(k))
            throw input_error("topology.structure.data", "expected the ids 0 to " + std::to_string(byId.size() - 1));
        if (batchOrder.empty() || byId[k].second != batchOrder.back()) {
            if (!batchOrder.empty() && byId[k].second < batchOrder.back())
                throw unsupported({"topology.structure.data",
                                   "batchId " + std::to_string(byId[k].second) + " at id " + std::to_string(k) +
                                       " after batchId " + std::to_string(batchOrder.back()) +
                                       ": each batch must be one run of consecutive ids, in increasing batchId order"});
            batchOrder.push_back(byId[k].second);
            batchStart.push_back(static_cast<int64_t>(k));
        }
    }
    batchStart.push_back(static_cast<int64_t>(byId.size()));
    const int batches = static_cast<int>(batchOrder.size());
    if (batches < ranks)
        throw unsupported({"topology.structure.data", std::to_string(batches) + " batch(es) cannot be spread over " +
                                                          std::to_string(ranks) + " ranks: every rank needs one"});

    // Rank r's batches: a contiguous block, the first B mod K ranks one more.
    auto firstBatch = [&](int r) { return r * (batches / ranks) + std::min(r, batches % ranks); };
    BatchShare share;
    for (int r = 0; r < ranks; ++r)
        share.particleCounts.push_back(batchStart[firstBatch(r + 1)] - batchStart[firstBatch(r)]);
    const Range range{batchStart[firstBatch(rank)], batchStart[firstBatch(rank + 1)]};
    share.firstId = range.first;
    share.batches.assign(batchOrder.begin() + firstBatch(rank), batchOrder.begin() + firstBatch(rank + 1));
    share.document = document;
    Splitter(range, share.batches).walk(share.document, "");
    return share;
}

}  // namespace structmd
