// LeftPack (core/left_pack.hpp) against element-by-element loops: the kept elements of
// every array, in order, for lengths that do and do not fill the last block.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "core/left_pack.hpp"

namespace structmd {
namespace {

template <class T>
void expect_packed_like_a_loop(double keepFraction, std::mt19937& rng) {
    std::bernoulli_distribution kept(keepFraction);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    for (int n = 0; n <= 3 * LeftPack<T>::kWidth + 1; ++n) {
        const size_t length = static_cast<size_t>(LeftPack<T>::padded(n));
        std::vector<T> a(length), b(length), keep(length, T(0));
        std::vector<T> expectedA, expectedB;
        for (int m = 0; m < n; ++m) {
            a[m] = T(value(rng));
            b[m] = T(value(rng));
            keep[m] = kept(rng) ? T(1) : T(0);
            if (keep[m] != T(0)) {
                expectedA.push_back(a[m]);
                expectedB.push_back(b[m]);
            }
        }
        T* const arrays[2] = {a.data(), b.data()};
        const int count = LeftPack<T>::pack(arrays, 2, keep.data(), n);
        ASSERT_EQ(count, static_cast<int>(expectedA.size())) << "n " << n;
        for (int m = 0; m < count; ++m) {
            EXPECT_EQ(a[m], expectedA[m]) << "n " << n << ", element " << m;
            EXPECT_EQ(b[m], expectedB[m]) << "n " << n << ", element " << m;
        }
    }
}

TEST(LeftPack, KeepsTheMarkedFloatsInOrder) {
    std::mt19937 rng(7);
    for (double fraction : {0.0, 0.3, 0.7, 1.0}) expect_packed_like_a_loop<float>(fraction, rng);
}

TEST(LeftPack, KeepsTheMarkedDoublesInOrder) {
    std::mt19937 rng(8);
    for (double fraction : {0.0, 0.3, 0.7, 1.0}) expect_packed_like_a_loop<double>(fraction, rng);
}

TEST(LeftPack, AppendsTheIndicesOfEveryMask) {
    for (unsigned mask = 0; mask < 256; ++mask) {
        std::vector<int32_t> out(8, -1);
        const int count = LeftPack<int32_t>::append_indices(out.data(), 1000, mask);
        std::vector<int32_t> expected;
        for (int e = 0; e < 8; ++e)
            if (mask >> e & 1u) expected.push_back(1000 + e);
        ASSERT_EQ(count, static_cast<int>(expected.size())) << "mask " << mask;
        for (int m = 0; m < count; ++m) EXPECT_EQ(out[m], expected[m]) << "mask " << mask;
    }
}

}  // namespace
}  // namespace structmd
