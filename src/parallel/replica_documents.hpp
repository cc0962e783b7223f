#pragma once
// Parallel tempering's input: the simulationStep entry whose registry entry runs replicas
// (steps/parallel_tempering.hpp), and the document each replica runs, the input at one of the entry's
// temperatures.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "input/description.hpp"

namespace structmd {

struct ReplicaExchangeSpec {
    std::string name;  // the simulationStep entry's
    int64_t interval = 0;  // steps between exchange attempts
    int64_t start = 0;  // attempts at the multiples of interval from start to end, both included
    int64_t end = 0;
    std::vector<double> temperatures;  // one replica each, in the input's units
    std::string outputPath;  // the acceptance measure, written by rank 0
    uint64_t seed = 0;  // the system's seed, which keys the exchanges' random numbers
};

// The simulationStep entry that runs the input as replicas (its registry entry's runsReplicas), or
// nullptr when there is none. Throws ERR_INPUT at the second one of two.
const input::ComponentEntry* replica_exchange_entry(const input::SystemDescription& system);

// That entry of `document`, read by its registry entry's schema. Throws ERR_INPUT with the JSON path
// for a malformed entry, ERR_UNSUPPORTED for a group other than "All" and for an input whose
// temperature does not come from the ensemble alone (an integrator's own "temperature").
ReplicaExchangeSpec read_replica_exchange(const input::ParsedDocument& document, const input::ComponentEntry& entry);

// The document of replica k, from the input's: without the entry, the ensemble at temperatures[k], its
// own seed (replicas must not share their noise), and every simulation step's outputFilePath with its
// file name prefixed "temperature<k>_" (configurations move between replicas; each replica keeps its
// temperature, so each file follows one temperature).
nlohmann::json replica_document(const nlohmann::json& document, const ReplicaExchangeSpec& spec, int k);

}  // namespace structmd
