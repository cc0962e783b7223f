// Asking the GPU for more memory than it has: a neighbour list whose radius spans the box gives each
// of 262,144 particles room for every other, about 275 GB, more than any one GPU holds today. The
// step that would build it fails with STRUCTMD_ERR_MEMORY naming the allocation, and the same
// handle then loads and steps a small system. Exits 77 (skipped) where no GPU is usable.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "robustness_support.hpp"

namespace structmd::robustness {
namespace {

constexpr const char* kCudaOptions = R"({"backend": "cuda", "log": "quiet"})";

std::string list_larger_than_the_device() {
    nlohmann::json document = nlohmann::json::parse(lattice_input(64, 3, "vv", 100));
    document["topology"]["forceField"]["nl"]["parameters"]["cutOffVerletFactor"] = 1000.0;
    return document.dump();
}

TEST(DeviceMemory, TooLargeAListIsErrMemoryAndTheHandleStaysUsable) {
    const host::Handle sim(kCudaOptions);
    ASSERT_EQ(structmd_load_string(sim.get(), list_larger_than_the_device().c_str()), STRUCTMD_OK)
        << structmd_last_error(sim.get());
    ASSERT_EQ(structmd_step(sim.get(), 1), STRUCTMD_ERR_MEMORY) << structmd_last_error(sim.get());
    const std::string message = structmd_last_error(sim.get());
    EXPECT_NE(message.find("bytes of device memory"), std::string::npos) << message;

    ASSERT_EQ(structmd_load_string(sim.get(), lattice_input(6, 3, "vv", 100).c_str()), STRUCTMD_OK)
        << structmd_last_error(sim.get());
    ASSERT_EQ(structmd_step(sim.get(), 20), STRUCTMD_OK) << structmd_last_error(sim.get());
    for (double x : positions(sim.get())) ASSERT_TRUE(std::isfinite(x));
    EXPECT_TRUE(std::isfinite(energy(sim.get(), "total")));
}

}  // namespace
}  // namespace structmd::robustness

int main(int argc, char** argv) {
    structmd_sim* probe = nullptr;
    if (structmd_create(structmd::robustness::kCudaOptions, &probe) != STRUCTMD_OK) {
        std::printf("no usable GPU: %s\n", structmd_last_error(nullptr));
        return 77;
    }
    structmd_destroy(probe);
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
