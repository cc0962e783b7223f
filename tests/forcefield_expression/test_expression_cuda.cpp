// CUDA against CPU for a scene of all five Expression components, in double: forces, the energy of
// each term and the total agree to 1e-10 relative. Exits with 77 (skipped for CTest) when no CUDA
// backend is usable.
#include <gtest/gtest.h>

#include <cstdio>

#include "expression_scenes.hpp"

namespace structmd_expression_test {
namespace {

const std::string& scene() {
    static const std::string forceField =
        neighbour_list() + ", " + expression_lj("pair", true) +
        ", \"bond2\": {\"type\": [\"Bond2\", \"Expression\"], \"parameters\": {\"energy\": \"k * (r - 1.1)^2 + exp(-r)\"}, "
        "\"labels\": [\"id_i\", \"id_j\", \"k\"], \"data\": [[0, 1, 2.0], [2, 3, 3.0], [4, 5, 1.5]]}"
        ", \"bond3\": {\"type\": [\"Bond3\", \"Expression\"], \"parameters\": {\"K\": 20.0, \"energy\": "
        "\"0.5 * K * (theta - t0)^2\"}, \"labels\": [\"id_i\", \"id_j\", \"id_k\", \"t0\"], \"data\": [[2, 3, 4, 1.9], [3, 4, 5, 2.2]]}"
        ", \"bond4\": {\"type\": [\"Bond4\", \"Expression\"], \"parameters\": {\"energy\": \"3 * (1 + cos(2 * phi - 0.4))\"}, "
        "\"labels\": [\"id_i\", \"id_j\", \"id_k\", \"id_l\"], \"data\": [[2, 3, 4, 5], [6, 2, 3, 7]]}"
        ", \"field\": {\"type\": [\"External\", \"Expression\"], \"parameters\": {\"energy\": "
        "\"0.1 * (x^2 + y^2) + select(step(z), z^2, 0.5 * z^2)\"}}";
    return forceField;
}

TEST(ExpressionBackends, CudaAgreesWithCpuInDouble) {
    for (const char* term : {"potential", "pair", "bond2", "bond3", "bond4", "field"}) {
        SCOPED_TRACE(term);
        const Evaluation cpu = evaluate(scene(), term, "double", "cpu");
        const Evaluation cuda = evaluate(scene(), term, "double", "cuda");
        ASSERT_EQ(cpu.status, STRUCTMD_OK) << cpu.error;
        ASSERT_EQ(cuda.status, STRUCTMD_OK) << cuda.error;
        EXPECT_LT(max_relative_deviation(cuda.forces, cpu.forces), 1e-10);
        EXPECT_LT(relative_deviation(cuda.energy, cpu.energy), 1e-10) << cuda.energy << " vs " << cpu.energy;
    }
}

TEST(ExpressionBackends, CudaRunsInSingleAndMixedPrecision) {
    for (const char* precision : {"single", "mixed"}) {
        SCOPED_TRACE(precision);
        const Evaluation cpu = evaluate(scene(), "potential", precision, "cpu");
        const Evaluation cuda = evaluate(scene(), "potential", precision, "cuda");
        ASSERT_EQ(cuda.status, STRUCTMD_OK) << cuda.error;
        EXPECT_LT(max_relative_deviation(cuda.forces, cpu.forces), 1e-4);
        EXPECT_LT(relative_deviation(cuda.energy, cpu.energy), 1e-4);
    }
}

}  // namespace
}  // namespace structmd_expression_test

int main(int argc, char** argv) { return structmd_physics::run_tests_if_cuda(argc, argv); }
