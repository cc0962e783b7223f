#include "parallel/load_over_ranks.hpp"

#include <algorithm>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "engines/make_engine.hpp"
#include "parallel/batch_split.hpp"
#include "parallel/batches_over_ranks.hpp"
#include "parallel/domain_spec.hpp"
#include "parallel/domain_support.hpp"
#include "parallel/domains_over_ranks.hpp"
#include "parallel/replica_documents.hpp"
#include "parallel/replica_exchange.hpp"
#include "simulation/read_simulation.hpp"

namespace structmd {

namespace {

// Malformed text, and numbers no double holds (1e3000: nlohmann's out_of_range), are the input's fault.
nlohmann::json parse(const std::string& text) {
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw input_error("", std::string("not valid JSON: ") + e.what());
    }
}

// One batch (no batchId, or one value in it): the system is split in space rather than by batch.
bool one_batch(const nlohmann::json& document) {
    if (!document.is_object() || !document.contains("topology") || !document["topology"].is_object()) return false;
    const nlohmann::json& topology = document["topology"];
    if (!topology.contains("structure") || !topology["structure"].is_object()) return false;
    const nlohmann::json& structure = topology["structure"];
    if (!structure.contains("labels") || !structure.contains("data") || !structure["labels"].is_array() ||
        !structure["data"].is_array())
        return false;
    const nlohmann::json& labels = structure["labels"];
    const auto column = std::find(labels.begin(), labels.end(), "batchId");
    if (column == labels.end()) return true;
    const auto k = static_cast<size_t>(column - labels.begin());
    std::optional<nlohmann::json> first;
    for (const nlohmann::json& row : structure["data"]) {
        if (!row.is_array() || k >= row.size()) return false;
        if (!first) first = row[k];
        else if (row[k] != *first) return false;
    }
    return true;
}

}  // namespace

std::unique_ptr<Simulation> load_over_ranks(const EngineOptions& options, const std::string& text,
                                            const ForceFieldComponents& components, const Logger& log,
                                            std::shared_ptr<const Communicator> comm) {
    // Parallel tempering: the document's replicas over the ranks. A cheap look first, so that
    // other inputs are not parsed twice.
    if (text.find("ReplicaExchange") != std::string::npos) {
        std::vector<std::unique_ptr<Simulation>> replicas;
        std::optional<ReplicaExchangeSpec> spec;
        run_together(*comm, [&] {
            nlohmann::json document = parse(text);
            spec = take_replica_exchange(document);
            if (!spec) return;
            const int count = static_cast<int>(spec->temperatures.size());
            if (count < comm->size())
                throw Error(STRUCTMD_ERR_UNSUPPORTED,
                            "simulationStep." + spec->name + ".parameters.temperatures: " + std::to_string(count) +
                                " replicas cannot be spread over " + std::to_string(comm->size()) +
                                " ranks: every rank needs one");
            for (int k = comm->rank(); k < count; k += comm->size())
                replicas.push_back(
                    load_simulation(options, replica_document(document, *spec, k).dump(), components, log));
        });
        if (spec) return std::make_unique<ReplicaExchange>(std::move(replicas), std::move(comm), std::move(*spec));
    }
    std::unique_ptr<Simulation> local;
    // One batch on several ranks: spatial domains (domains_over_ranks.hpp).
    if (comm->size() > 1) {
        std::optional<DomainSpec> domains;
        run_together(*comm, [&] {
            const nlohmann::json document = parse(text);
            if (!one_batch(document)) return;
            // The reader first, so that bad input is named by its JSON path before the domains
            // look at the document.
            SimulationSpec spec = read_simulation(text, log, components.reader());
            check_domain_support(document);
            domains.emplace(static_cast<const SystemSpec&>(spec));
            local = make_simulation(options, std::move(spec), components, log);
        });
        if (domains)
            return std::make_unique<DomainsOverRanks>(options, std::move(*domains), std::move(local), components, log,
                                                      std::move(comm));
    }
    BatchShare share;
    // A rank whose share fails to load (its own input error, memory) fails every rank's load.
    run_together(*comm, [&] {
        if (comm->size() == 1) {
            local = load_simulation(options, text, components, log);
            return;
        }
        share = split_batches(parse(text), comm->rank(), comm->size());
        local = load_simulation(options, share.document.dump(), components, log, share.firstId);
    });
    if (comm->size() == 1) return local;
    log.info("MPI rank " + std::to_string(comm->rank()) + " of " + std::to_string(comm->size()) + ": " +
             std::to_string(share.batches.size()) + " batch(es), particles " + std::to_string(share.firstId) + " to " +
             std::to_string(share.firstId + local->particle_count() - 1));
    return std::make_unique<BatchesOverRanks>(std::move(local), std::move(comm), std::move(share.particleCounts),
                                              std::move(share.batches));
}

}  // namespace structmd
