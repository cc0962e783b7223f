// The batch split's refusals: what names particles by id where no share can renumber it, and a
// layout of batches the ranks cannot share, each named by its JSON path.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "parallel/batch_split.hpp"

namespace structmd {
namespace {

using json = nlohmann::json;

// Two batches of two particles, with the given force field and simulation steps.
json document(const json& forceField, const json& steps = json::object()) {
    return {{"topology",
             {{"structure",
               {{"labels", {"id", "type", "batchId"}}, {"data", {{0, "A", 0}, {1, "A", 0}, {2, "A", 1}, {3, "A", 1}}}}},
              {"forceField", forceField}}},
            {"simulationStep", steps}};
}

// The split's message for rank 0 of `ranks`, or "" when it splits.
std::string refusal(const json& input, int ranks = 2) {
    try {
        split_batches(input, 0, ranks);
    } catch (const Error& error) {
        EXPECT_EQ(error.status(), STRUCTMD_ERR_UNSUPPORTED) << error.what();
        return error.what();
    }
    return "";
}

const json kBond = {{"type", {"Bond2", "Harmonic"}}, {"labels", {"id_i", "id_j", "K", "r0"}}};

TEST(BatchSplit, ABondWithinAShareIsKeptWithItsIdsShifted) {
    json bonds = kBond;
    bonds["data"] = {{0, 1, 1.0, 1.0}, {2, 3, 1.0, 1.0}};
    const BatchShare share = split_batches(document({{"bonds", bonds}}), 1, 2);
    EXPECT_EQ(share.document["topology"]["forceField"]["bonds"]["data"], json({{0, 1, 1.0, 1.0}}));
}

TEST(BatchSplit, WhatNamesParticlesByIdIsRefusedByItsPath) {
    json across = kBond;
    across["data"] = {{1, 2, 1.0, 1.0}};
    EXPECT_EQ(refusal(document({{"bonds", across}})),
              "topology.forceField.bonds.data[0]: an entry between particles of batches on different ranks (batches "
              "over MPI ranks)");
    const json set = {{"type", {"Set1", "ConstantForceOverCenterOfMass"}}, {"labels", {"idSet_i", "force"}},
                      {"data", {{{0, 1}, {1, 0, 0}}}}};
    EXPECT_EQ(refusal(document({{"set", set}})),
              "topology.forceField.set.labels: column 'idSet_i' names particles by id (batches over MPI ranks)");
    const json groups = {{"type", {"Groups", "GroupsList"}}, {"labels", {"name", "type", "selection"}},
                         {"data", {{"g", "Ids", {0, 1}}}}};
    EXPECT_EQ(refusal(document({{"groups", groups}})),
              "topology.forceField.groups.data[0]: a group selected by particle ids (batches over MPI ranks)");
}

TEST(BatchSplit, AStepThatWouldReadOneShareIsRefused) {
    const json ofGroup = {{"type", {"ThermodynamicMeasure", "ThermodynamicQuantityMeasure"}},
                          {"parameters", {{"intervalStep", 1}, {"group", "g"}}}};
    EXPECT_EQ(refusal(document(json::object(), {{"measure", ofGroup}})),
              "simulationStep.measure.parameters.group: a simulation step of a group other than \"All\" (batches "
              "over MPI ranks)");
    const json table = {{"type", {"GeometricalMeasure", "DistancesMeasure"}},
                        {"parameters", {{"intervalStep", 1}}},
                        {"labels", {"id_i", "id_j"}},
                        {"data", {{0, 1}}}};
    EXPECT_EQ(refusal(document(json::object(), {{"distances", table}})),
              "simulationStep.distances.labels: a simulation step with a table of particles (batches over MPI ranks)");
}

TEST(BatchSplit, FewerBatchesThanRanksAreRefused) {
    EXPECT_EQ(refusal(document(json::object()), 3),
              "topology.structure.data: 2 batch(es) cannot be spread over 3 ranks: every rank needs one (batches over "
              "MPI ranks)");
}

}  // namespace
}  // namespace structmd
