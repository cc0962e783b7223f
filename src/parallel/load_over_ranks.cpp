#include "parallel/load_over_ranks.hpp"

#include <algorithm>
#include <functional>
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

// One batch (no batchId, or one value in it): the system is split in space rather than by batch.
bool one_batch(const input::SystemDescription& system) {
    return std::adjacent_find(system.batchId.begin(), system.batchId.end(), std::not_equal_to<int32_t>()) ==
           system.batchId.end();
}

}  // namespace

std::unique_ptr<Simulation> load_over_ranks(const EngineOptions& options, const std::string& text,
                                            const ForceFieldComponents& components, const Logger& log,
                                            std::shared_ptr<const Communicator> comm) {
    // Parsed once: every rank's way of running the input is decided from its description. A rank whose
    // load fails (its own input error, memory) fails every rank's load.
    std::optional<input::ParsedDocument> document;
    run_together(*comm, [&] { document.emplace(input::parse_document(text)); });
    // Parallel tempering: the document's replicas over the ranks.
    const input::ComponentEntry* exchange = nullptr;
    run_together(*comm, [&] { exchange = replica_exchange_entry(document->system); });
    if (exchange) {
        std::vector<std::unique_ptr<Simulation>> replicas;
        ReplicaExchangeSpec spec;
        run_together(*comm, [&] {
            spec = read_replica_exchange(*document, *exchange);
            const int count = static_cast<int>(spec.temperatures.size());
            if (count < comm->size())
                throw Error(STRUCTMD_ERR_UNSUPPORTED,
                            "simulationStep." + spec.name + ".parameters.temperatures: " + std::to_string(count) +
                                " replicas cannot be spread over " + std::to_string(comm->size()) +
                                " ranks: every rank needs one");
            for (int k = comm->rank(); k < count; k += comm->size())
                replicas.push_back(load_simulation(options, replica_document(document->root.json(), spec, k).dump(), components, log));
        });
        return std::make_unique<ReplicaExchange>(std::move(replicas), std::move(comm), std::move(spec));
    }
    std::unique_ptr<LocalEngine> local;
    // One batch on several ranks: spatial domains (domains_over_ranks.hpp).
    if (comm->size() > 1 && one_batch(document->system)) {
        std::optional<DomainSpec> domains;
        run_together(*comm, [&] {
            // The reader first, so that bad input is named by its JSON path before the domains
            // look at what it read.
            SimulationSpec spec = read_simulation(*document, log, components);
            check_domain_support(*document, spec, components.reader());
            domains.emplace(static_cast<const SystemSpec&>(spec));
            local = make_simulation(options, std::move(spec), components, log);
        });
        return std::make_unique<DomainsOverRanks>(options, std::move(*domains), std::move(local), components, log,
                                                  std::move(comm));
    }
    BatchShare share;
    run_together(*comm, [&] {
        if (comm->size() == 1) {
            local = make_simulation(options, read_simulation(*document, log, components), components, log);
            return;
        }
        share = split_batches(document->root.json(), comm->rank(), comm->size());
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
