#include "parallel/batch_split.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace structmd {

namespace {

using json = nlohmann::json;

Error unsupported(const std::string& path, const std::string& what) {
    return Error(STRUCTMD_ERR_UNSUPPORTED, path + ": " + what + " (batches over MPI ranks)");
}

int column(const json& labels, const std::string& name) {
    for (size_t k = 0; k < labels.size(); ++k)
        if (labels[k].is_string() && labels[k].get<std::string>() == name) return static_cast<int>(k);
    return -1;
}

// Labels that name particles by id, beside those the split rewrites.
bool names_particles(const std::string& label) {
    if (label == "batchId" || label == "modelId" || label == "resId" || label == "chainId") return false;
    return label.rfind("id", 0) == 0 || (label.size() > 2 && label.compare(label.size() - 2, 2, "Id") == 0);
}

// The selection types of ["Groups","GroupsList"] that list particle ids.
bool selects_ids(const json& type) {
    return type.is_string() && (type == "Ids" || type == "notIds");
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
        // The simulation steps see the whole system (batches_over_ranks.hpp), so what they read
        // of the document must not depend on the share.
        const bool step = path.rfind("simulationStep.", 0) == 0;
        if (step && node.contains("parameters") && node["parameters"].is_object()) {
            const json& parameters = node["parameters"];
            if (parameters.contains("group") && parameters["group"] != "All")
                throw unsupported(path + ".parameters.group", "a simulation step of a group other than \"All\"");
        }
        if (step && node.contains("labels")) {
            // Its table stays whole; one that names particles by id is refused.
            for (const json& label : node["labels"])
                if (label.is_string() && (label == "id" || names_particles(label.get<std::string>())))
                    throw unsupported(path + ".labels", "a simulation step with a table of particles");
            if (node.contains("data")) refuse_id_selections(node, path);
            return;
        }
        if (node.contains("labels") && node.contains("data") && node["labels"].is_array() && node["data"].is_array()) {
            table(node, path);
            return;
        }
        for (auto it = node.begin(); it != node.end(); ++it) walk(it.value(), path.empty() ? it.key() : path + "." + it.key());
    }

private:
    // Groups of ["Groups","GroupsList"] that list particle ids.
    static void refuse_id_selections(const json& node, const std::string& path) {
        const json& labels = node["labels"];
        const json& data = node["data"];
        const int typeColumn = column(labels, "type"), selection = column(labels, "selection");
        if (selection < 0 || typeColumn < 0 || !data.is_array()) return;
        for (size_t r = 0; r < data.size(); ++r)
            if (data[r].is_array() && typeColumn < static_cast<int>(data[r].size()) && selects_ids(data[r][typeColumn]))
                throw unsupported(path + ".data[" + std::to_string(r) + "]", "a group selected by particle ids");
    }

    // One labelled table: rows of particles or bonds kept with shifted ids, batched rows kept for this
    // rank's batches.
    void table(json& node, const std::string& path) {
        const json& labels = node["labels"];
        json& data = node["data"];
        std::vector<int> idColumns;
        for (size_t k = 0; k < labels.size(); ++k) {
            if (!labels[k].is_string()) continue;
            const std::string label = labels[k].get<std::string>();
            if (label == "id" || (label.rfind("id_", 0) == 0 && label.size() == 4))
                idColumns.push_back(static_cast<int>(k));
            else if (names_particles(label))
                throw unsupported(path + ".labels", "column '" + label + "' names particles by id");
        }
        refuse_id_selections(node, path);
        const int batchColumn = column(labels, "batchId");
        json kept = json::array();
        for (size_t r = 0; r < data.size(); ++r) {
            const std::string rowPath = path + ".data[" + std::to_string(r) + "]";
            json row = data[r];
            if (!idColumns.empty()) {
                int inside = 0;
                for (int col : idColumns) inside += range_.holds(id_at(row, col, rowPath)) ? 1 : 0;
                if (inside == 0) continue;
                if (inside != static_cast<int>(idColumns.size()))
                    throw unsupported(rowPath, "an entry between particles of batches on different ranks");
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
                throw unsupported("topology.structure.data",
                                  "batchId " + std::to_string(byId[k].second) + " at id " + std::to_string(k) +
                                      " after batchId " + std::to_string(batchOrder.back()) +
                                      ": each batch must be one run of consecutive ids, in increasing batchId order");
            batchOrder.push_back(byId[k].second);
            batchStart.push_back(static_cast<int64_t>(k));
        }
    }
    batchStart.push_back(static_cast<int64_t>(byId.size()));
    const int batches = static_cast<int>(batchOrder.size());
    if (batches < ranks)
        throw unsupported("topology.structure.data", std::to_string(batches) + " batch(es) cannot be spread over " +
                                                         std::to_string(ranks) + " ranks: every rank needs one");

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
