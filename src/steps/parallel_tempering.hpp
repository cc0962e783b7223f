#pragma once
// ["ReplicaExchange","ParallelTempering"]: the whole input run as one replica per temperature
// (parallel/replica_exchange.hpp). No engine runs a step of it; its entry declares the parameters that
// parallel/replica_documents.cpp reads and that it runs replicas.
#include "steps/simulation_step_registry.hpp"

namespace structmd {

SimulationStepEntry parallel_tempering_entry();

}  // namespace structmd
