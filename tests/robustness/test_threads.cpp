// Independent handles driven from several std::threads at once: each thread loads its own input,
// steps it in chunks and reads positions and energies between chunks; the record must equal, bit for
// bit, that of the same input run alone on the main thread beforehand. Langevin noise comes from each
// input's seed, so any state shared between handles (a random stream, a scratch buffer, a cached
// list) would change some record. Run under ThreadSanitizer by scripts/tsan.sh.
#include <atomic>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "robustness_support.hpp"

namespace {

using namespace structmd::robustness;
using structmd::host::check;
using structmd::host::Handle;

constexpr int kThreads = 4;
constexpr int kChunks = 10;
constexpr int64_t kStepsPerChunk = 50;

// What a run reads back between its chunks of steps.
struct Record {
    std::vector<double> positions;
    std::vector<double> energies;  // potential, kinetic per chunk
    bool operator==(const Record& other) const { return positions == other.positions && energies == other.energies; }
};

std::string input_of(int thread) {
    // Alternate integrators so threads run different code at the same time; seeds make each distinct.
    return lattice_input(6, 100 + static_cast<uint64_t>(thread), thread % 2 == 0 ? "bbk" : "vv", 1000);
}

Record run(const std::string& input) {
    Handle sim(kHandleOptions);
    check(structmd_load_string(sim.get(), input.c_str()), sim.get(), "structmd_load_string");
    Record record;
    for (int chunk = 0; chunk < kChunks; ++chunk) {
        check(structmd_step(sim.get(), kStepsPerChunk), sim.get(), "structmd_step");
        const std::vector<double> xyz = positions(sim.get());
        record.positions.insert(record.positions.end(), xyz.begin(), xyz.end());
        record.energies.push_back(energy(sim.get(), "potential"));
        record.energies.push_back(energy(sim.get(), "kinetic"));
    }
    return record;
}

TEST(Threads, HandlesOnSeveralThreadsMatchSingleThreadedRuns) {
    std::vector<std::string> inputs;
    std::vector<Record> alone;
    for (int t = 0; t < kThreads; ++t) {
        inputs.push_back(input_of(t));
        alone.push_back(run(inputs.back()));
    }
    // Different seeds must give different records, or the comparison below could not see a mix-up.
    ASSERT_FALSE(alone[0] == alone[2]);

    std::vector<Record> together(kThreads);
    std::vector<std::string> failures(kThreads);
    std::vector<std::thread> threads;
    std::atomic<int> arrived{0};
    for (int t = 0; t < kThreads; ++t)
        threads.emplace_back([&, t] {
            // All threads start together, so their calls overlap.
            ++arrived;
            while (arrived.load() < kThreads) std::this_thread::yield();
            try {
                together[t] = run(inputs[t]);
            } catch (const std::exception& e) {
                failures[t] = e.what();
            }
        });
    for (std::thread& thread : threads) thread.join();

    for (int t = 0; t < kThreads; ++t) {
        EXPECT_EQ(failures[t], "") << "thread " << t;
        EXPECT_TRUE(together[t] == alone[t]) << "thread " << t << " differs from its single-threaded run";
    }
}

// structmd_last_error(NULL) is per thread: each thread's failed create keeps its own message.
TEST(Threads, FailedCreatesKeepTheirMessagePerThread) {
    std::vector<std::string> messages(kThreads);
    std::vector<structmd_status> statuses(kThreads);
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
        threads.emplace_back([&, t] {
            const std::string key = "unknown_option_" + std::to_string(t);
            const std::string options = "{\"" + key + "\": 1}";
            structmd_sim* sim = nullptr;
            for (int repeat = 0; repeat < 200; ++repeat) statuses[t] = structmd_create(options.c_str(), &sim);
            messages[t] = structmd_last_error(nullptr);
        });
    for (std::thread& thread : threads) thread.join();
    for (int t = 0; t < kThreads; ++t) {
        EXPECT_EQ(statuses[t], STRUCTMD_ERR_ARGUMENT);
        EXPECT_NE(messages[t].find("unknown_option_" + std::to_string(t)), std::string::npos) << messages[t];
    }
}

}  // namespace
