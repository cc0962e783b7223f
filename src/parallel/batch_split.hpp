#pragma once
// Batches over ranks: the share of an input document's batches (topology.structure's batchId) that
// one rank of K simulates, as a document of its own. Batches never interact through pairs, so a rank
// simulating only its batches computes what the whole system would for them.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace structmd {

struct BatchShare {
    nlohmann::json document;             // the input with only this rank's particles, ids from 0
    int64_t firstId = 0;                 // the global id of its particle 0
    std::vector<int64_t> particleCounts;  // every rank's particle count, in rank order
    std::vector<int> batches;             // the batchId values this rank holds, increasing
};

// Rank `rank` of `ranks` takes a contiguous block of the batches in increasing batchId order (the
// first B mod K ranks one batch more). Each batch must be one run of consecutive ids, the batches in
// increasing order of batchId (as UAMMD-structured's batched inputs are written), so that every
// share is a contiguous range of ids and the gathered arrays are in the one-rank order. Rows that
// name particles are kept with ids shifted (state, topology.structure, the id_i... columns of bonded
// entries) or dropped when of another rank's batches (tables with a batchId column). Anything else
// that names particles by id is refused: STRUCTMD_ERR_UNSUPPORTED with its JSON path, as is a bond
// between two shares and fewer batches than ranks.
BatchShare split_batches(const nlohmann::json& document, int rank, int ranks);

}  // namespace structmd
