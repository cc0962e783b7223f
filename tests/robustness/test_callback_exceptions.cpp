// A C++ host's force callback that throws: the exception stops at the library's boundary as
// STRUCTMD_ERR_CALLBACK quoting what(), the step is undone, and the handle steps on once the
// callback is replaced.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "robustness_support.hpp"

using namespace structmd::robustness;

namespace {

int32_t throws_at_step_three(const double*, double*, int64_t, double*, double*, int64_t step, void*) {
    if (step == 3) throw std::runtime_error("the solver ran out of iterations");
    return 0;
}

int32_t throws_a_number(const double*, double*, int64_t, double*, double*, int64_t, void*) { throw 42; }

int32_t device_throws(const void*, void*, int64_t, int32_t, double*, double*, int64_t, void*, void*) {
    throw std::logic_error("no device here");
}

struct Loaded : ::testing::Test {
    void SetUp() override {
        ASSERT_EQ(structmd_create(kHandleOptions, &sim), STRUCTMD_OK);
        ASSERT_EQ(structmd_load_string(sim, lattice_input(6, 1, "vv", 100).c_str()), STRUCTMD_OK);
    }
    void TearDown() override { structmd_destroy(sim); }
    int64_t step() {
        int64_t value = -1;
        structmd_get_step(sim, &value);
        return value;
    }
    structmd_sim* sim = nullptr;
};

TEST_F(Loaded, ExceptionBecomesCallbackErrorAndTheStepIsUndone) {
    ASSERT_EQ(structmd_step(sim, 1), STRUCTMD_OK);
    const std::vector<double> before = positions(sim);
    ASSERT_EQ(structmd_set_force_callback(sim, throws_at_step_three, nullptr), STRUCTMD_OK);
    EXPECT_EQ(structmd_step(sim, 5), STRUCTMD_ERR_CALLBACK);
    const std::string message = structmd_last_error(sim);
    EXPECT_NE(message.find("step 3: the force callback threw: the solver ran out of iterations"), std::string::npos)
        << message;
    EXPECT_EQ(step(), 1);
    EXPECT_EQ(positions(sim), before);
    ASSERT_EQ(structmd_set_force_callback(sim, nullptr, nullptr), STRUCTMD_OK);
    EXPECT_EQ(structmd_step(sim, 5), STRUCTMD_OK);
    EXPECT_EQ(step(), 6);
}

TEST_F(Loaded, ExceptionOfAnyTypeIsCaught) {
    ASSERT_EQ(structmd_set_force_callback(sim, throws_a_number, nullptr), STRUCTMD_OK);
    std::vector<double> f(3 * 216);
    EXPECT_EQ(structmd_get_forces(sim, f.data(), 216), STRUCTMD_ERR_CALLBACK);
    EXPECT_NE(std::string(structmd_last_error(sim)).find("not a std::exception"), std::string::npos);
}

TEST_F(Loaded, DeviceCallbackExceptionIsCaughtToo) {
    ASSERT_EQ(structmd_set_device_force_callback(sim, device_throws, nullptr), STRUCTMD_OK);
    EXPECT_EQ(structmd_compute(sim, STRUCTMD_FORCES), STRUCTMD_ERR_CALLBACK);
    EXPECT_NE(std::string(structmd_last_error(sim)).find("device force callback threw: no device here"),
              std::string::npos);
    EXPECT_EQ(structmd_step(sim, 2), STRUCTMD_ERR_CALLBACK);
    EXPECT_EQ(step(), 0);
}

}  // namespace
