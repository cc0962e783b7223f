#pragma once
// Parallel tempering's input: the ["ReplicaExchange","ParallelTempering"] entry of simulationStep,
// and the document each replica runs, the input at one of the entry's temperatures.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "input/description.hpp"

namespace structmd {

struct ReplicaExchangeSpec {
    std::string name;  // the simulationStep entry's
    int64_t interval = 0;  // steps between exchange attempts
    std::vector<double> temperatures;  // one replica each, in the input's units
    std::string outputPath;  // the acceptance measure, written by rank 0
    uint64_t seed = 0;  // the system's seed, which keys the exchanges' random numbers
};

// Whether the input asks for parallel tempering: a simulationStep entry of its key.
bool asks_for_replicas(const input::SystemDescription& system);

// The entry, removed from the document, which must have one (asks_for_replicas). Throws ERR_INPUT
// with the JSON path for a malformed entry, ERR_UNSUPPORTED for an input whose temperature does not
// come from the ensemble alone (an integrator's own "temperature").
ReplicaExchangeSpec take_replica_exchange(nlohmann::json& document);

// The document of replica k: the ensemble at temperatures[k], its own seed (replicas must not share
// their noise), and every simulation step's outputFilePath with its file name prefixed
// "temperature<k>_" (configurations move between replicas; each replica keeps its temperature, so
// each file follows one temperature).
nlohmann::json replica_document(const nlohmann::json& document, const ReplicaExchangeSpec& spec, int k);

}  // namespace structmd
