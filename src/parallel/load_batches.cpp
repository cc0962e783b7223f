#include "parallel/load_batches.hpp"

#include <nlohmann/json.hpp>

#include "engines/make_engine.hpp"
#include "parallel/batch_split.hpp"
#include "parallel/batches_over_ranks.hpp"

namespace structmd {

std::unique_ptr<Simulation> load_over_ranks(const EngineOptions& options, const std::string& text,
                                            const ForceFieldComponents& components, const Logger& log,
                                            std::shared_ptr<const Communicator> comm) {
    std::unique_ptr<Simulation> local;
    BatchShare share;
    // A rank whose share fails to load (its own input error, memory) fails every rank's load.
    run_together(*comm, [&] {
        if (comm->size() == 1) {
            local = load_simulation(options, text, components, log);
            return;
        }
        nlohmann::json document;
        try {
            document = nlohmann::json::parse(text);
        } catch (const nlohmann::json::parse_error& e) {
            throw input_error("", std::string("not valid JSON: ") + e.what());
        }
        share = split_batches(document, comm->rank(), comm->size());
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
