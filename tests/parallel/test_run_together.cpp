// run_together_max (parallel/communicator.hpp): the one collective a spatial domain's step makes
// returns the largest value over the ranks and raises, on every rank, the first failed rank's error.
// The other rank is a stand-in communicator that answers as rank 1 of 2 would.
#include <gtest/gtest.h>

#include <new>
#include <string>
#include <vector>

#include "parallel/communicator.hpp"

namespace structmd {
namespace {

// Rank 0 of two; rank 1's part of every gather is `peerValue`, and it failed with `peerReport`
// ("<status> <message>") when that is not empty.
class TwoRanks final : public Communicator {
public:
    double peerValue = 0.0;
    std::string peerReport;

    int rank() const override { return 0; }
    int size() const override { return 2; }
    int node_rank() const override { return 0; }
    void all_gather(const double* mine, double* all, const std::vector<int64_t>& counts) const override {
        ASSERT_EQ(counts, (std::vector<int64_t>{2, 2}));
        all[0] = mine[0];
        all[1] = mine[1];
        all[2] = peerReport.empty() ? 2.0 : 1.0;
        all[3] = peerValue;
    }
    void all_gather(const int32_t*, int32_t*, const std::vector<int64_t>&) const override { FAIL(); }
    void all_sum(double*, int) const override { FAIL(); }
    int64_t all_min(int64_t) const override { ADD_FAILURE(); return 0; }
    int64_t all_max(int64_t) const override { ADD_FAILURE(); return 0; }
    void broadcast(std::string& bytes, int root) const override {
        if (root == 1) bytes = peerReport;
    }
    void send_receive(const double*, double*, int64_t, int) const override { FAIL(); }
    void shift(const double*, int64_t, int, double*, int64_t, int) const override { FAIL(); }
    void shift(const unsigned char*, int64_t, int, unsigned char*, int64_t, int) const override { FAIL(); }
};

TEST(RunTogetherMax, ReturnsTheLargestValueOverTheRanks) {
    TwoRanks comm;
    comm.peerValue = 2.5;
    EXPECT_EQ(run_together_max(comm, [] { return 1.0; }), 2.5);
    comm.peerValue = 0.5;
    EXPECT_EQ(run_together_max(comm, [] { return 1.0; }), 1.0);
}

TEST(RunTogetherMax, AFailureHereIsThrownWithItsStatus) {
    TwoRanks comm;
    try {
        run_together_max(comm, []() -> double { throw Error(STRUCTMD_ERR_NUMERICAL, "blew up"); });
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), STRUCTMD_ERR_NUMERICAL);
        EXPECT_STREQ(e.what(), "blew up");
    }
    try {
        run_together_max(comm, []() -> double { throw std::bad_alloc(); });
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), STRUCTMD_ERR_MEMORY);
    }
}

TEST(RunTogetherMax, AFailureOnAnotherRankIsThrownHereNamingIt) {
    TwoRanks comm;
    comm.peerReport = std::to_string(static_cast<int>(STRUCTMD_ERR_DEVICE)) + " out of GPU memory";
    try {
        run_together_max(comm, [] { return 1.0; });
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(e.status(), STRUCTMD_ERR_DEVICE);
        EXPECT_STREQ(e.what(), "out of GPU memory (on MPI rank 1)");
    }
}

}  // namespace
}  // namespace structmd
