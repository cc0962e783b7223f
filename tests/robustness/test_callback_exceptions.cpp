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

// A callback that calls back into its own handle: a load, a step, a getter that would evaluate the
// forces again and a destroy are each refused (STATE; destroy does nothing), so the engine is never
// pulled away under its own evaluation; only structmd_set_callback_error is taken (issue 37,
// defect 11).
namespace {

struct Reentry {
    structmd_sim* sim = nullptr;
    std::vector<structmd_status> statuses;
    std::string message;
};

int32_t calls_its_own_handle(const double*, double*, int64_t n, double*, double*, int64_t, void* data) {
    auto* r = static_cast<Reentry*>(data);
    std::vector<double> xyz(3 * n);
    r->statuses = {structmd_get_positions(r->sim, xyz.data(), n), structmd_step(r->sim, 1),
                   structmd_load_string(r->sim, "{}"), structmd_set_callback_error(r->sim, "unused")};
    r->message = structmd_last_error(r->sim);
    structmd_destroy(r->sim);
    return 0;
}

}  // namespace

TEST_F(Loaded, ACallbackCallingItsOwnHandleIsRefusedAndTheHandleLivesOn) {
    Reentry reentry{sim, {}, {}};
    ASSERT_EQ(structmd_set_force_callback(sim, calls_its_own_handle, &reentry), STRUCTMD_OK);
    ASSERT_EQ(structmd_step(sim, 2), STRUCTMD_OK) << structmd_last_error(sim);
    EXPECT_EQ(reentry.statuses, (std::vector<structmd_status>{STRUCTMD_ERR_STATE, STRUCTMD_ERR_STATE,
                                                              STRUCTMD_ERR_STATE, STRUCTMD_OK}));
    EXPECT_NE(reentry.message.find("inside a force callback"), std::string::npos) << reentry.message;
    EXPECT_NE(std::string(structmd_last_error(nullptr)).find("structmd_destroy: not available inside a force callback"),
              std::string::npos);
    ASSERT_EQ(structmd_set_force_callback(sim, nullptr, nullptr), STRUCTMD_OK);
    EXPECT_EQ(structmd_step(sim, 3), STRUCTMD_OK);
    EXPECT_EQ(step(), 5);
}
