// 1,000 create / failed load / load / step / read / destroy cycles in one process: resident memory
// after the last cycle may exceed that after cycle 100 by at most kAllowedGrowthKiB. The first
// 100 cycles let the allocator and the OpenMP runtime reach their working size; a leak of anything
// a cycle allocates (a simulation of 1,000 particles holds a few hundred KiB) would add far more.
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "robustness_support.hpp"

namespace {

using namespace structmd::robustness;
using structmd::host::check;

constexpr int kCycles = 1000;
constexpr int kWarmUpCycles = 100;
constexpr long kAllowedGrowthKiB = 1024;  // about 1 KiB per measured cycle

long resident_kib() {
    long pages = 0, resident = 0;
    std::ifstream("/proc/self/statm") >> pages >> resident;
    return resident * (::sysconf(_SC_PAGESIZE) / 1024);
}

void one_cycle(const std::string& good) {
    structmd_sim* sim = nullptr;
    check(structmd_create(kHandleOptions, &sim), nullptr, "structmd_create");
    // The error path allocates too (a parsed document, a message): it must give it all back.
    EXPECT_EQ(structmd_load_string(sim, "{\"system\": 1}"), STRUCTMD_ERR_INPUT);
    check(structmd_load_string(sim, good.c_str()), sim, "structmd_load_string");
    check(structmd_step(sim, 5), sim, "structmd_step");
    EXPECT_TRUE(std::isfinite(energy(sim, "total")));
    EXPECT_EQ(positions(sim).size(), 3000u);
    structmd_destroy(sim);
}

TEST(LifecycleMemory, ResidentMemoryStaysFlatOverAThousandCycles) {
    const std::string good = lattice_input(10, 5, "vv", 1000);
    for (int cycle = 0; cycle < kWarmUpCycles; ++cycle) one_cycle(good);
    const long afterWarmUp = resident_kib();
    for (int cycle = kWarmUpCycles; cycle < kCycles; ++cycle) one_cycle(good);
    const long afterAll = resident_kib();
    RecordProperty("resident_kib_after_warm_up", std::to_string(afterWarmUp));
    RecordProperty("resident_kib_after_all", std::to_string(afterAll));
    EXPECT_LE(afterAll - afterWarmUp, kAllowedGrowthKiB)
        << "resident memory grew from " << afterWarmUp << " KiB after cycle " << kWarmUpCycles << " to " << afterAll
        << " KiB after cycle " << kCycles;
}

}  // namespace
