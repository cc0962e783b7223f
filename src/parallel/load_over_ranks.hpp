#pragma once
// Loading an input over the ranks of a handle's communicator (single_process() for a handle without
// one): an input with parallel tempering as replicas over the ranks (replica_exchange.hpp); else one
// rank loads it whole, and several spread its batches over themselves (batch_split.hpp,
// batches_over_ranks.hpp). Collective.
#include <memory>
#include <string>

#include "core/logger.hpp"
#include "engines/engine_options.hpp"
#include "forcefield/component_set.hpp"
#include "parallel/communicator.hpp"
#include "simulation/simulation.hpp"

namespace structmd {

std::unique_ptr<Simulation> load_over_ranks(const EngineOptions& options, const std::string& text,
                                            const ForceFieldComponents& components, const Logger& log,
                                            std::shared_ptr<const Communicator> comm);

}  // namespace structmd
