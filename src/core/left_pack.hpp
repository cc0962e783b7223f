#pragma once
// Moving the kept elements of a few parallel arrays to their front, in order, a 32-byte block at a
// time: the block's keep mask picks a permutation from a table, one permute and one store per
// array and block (vpermd under AVX2). Element by element, each kept element costs a load and a
// store per array, and the stores' dependence on the loads bounded the CPU pair kernel.
#include <cstdint>
#include <cstring>

namespace structmd {

template <class T>
class LeftPack {
public:
    static constexpr int kWidth = 32 / static_cast<int>(sizeof(T));  // elements per block

    // Arrays passed to pack hold n rounded up to a block, plus one block: the last store of a
    // block is whole.
    static constexpr int padded(int n) { return (n + kWidth - 1) / kWidth * kWidth + kWidth; }

    // Packs the elements m < n of each of the `count` arrays with keep[m] != 0 to the array's front,
    // in order, and returns their number. keep must be zero from n to n rounded up to a block; it
    // is not moved.
    static int pack(T* const* arrays, int count, const T* keep, int n) {
        int kept = 0;
        for (int m = 0; m < n; m += kWidth) {
            unsigned mask = 0;
            for (int e = 0; e < kWidth; ++e) mask |= static_cast<unsigned>(keep[m + e] != T(0)) << e;
#if defined(__GNUC__) && !defined(__clang__)
            Words order;
            std::memcpy(&order, kTable.words[mask], sizeof(Words));
            for (int a = 0; a < count; ++a) {
                Words block;
                std::memcpy(&block, arrays[a] + m, sizeof(Words));
                block = __builtin_shuffle(block, order);
                std::memcpy(arrays[a] + kept, &block, sizeof(Words));
            }
            kept += __builtin_popcount(mask);
#else
            for (int e = 0; e < kWidth; ++e) {
                for (int a = 0; a < count; ++a) arrays[a][kept] = arrays[a][m + e];
                kept += static_cast<int>(mask >> e & 1u);
            }
#endif
        }
        return kept;
    }

    // Writes base + e for each bit e set in an 8-bit mask to out, in order (eight places written),
    // and returns their number: the appending of a block's accepted candidates, branch-free.
    static int append_indices(int32_t* out, int32_t base, unsigned mask) {
        static_assert(sizeof(T) == 4, "indices of 32-bit elements");
#if defined(__GNUC__) && !defined(__clang__)
        Words order;
        std::memcpy(&order, kTable.words[mask], sizeof(Words));
        order += static_cast<uint32_t>(base);
        std::memcpy(out, &order, sizeof(Words));
        return __builtin_popcount(mask);
#else
        int count = 0;
        for (int e = 0; e < 8; ++e) {
            out[count] = base + e;
            count += static_cast<int>(mask >> e & 1u);
        }
        return count;
#endif
    }

private:
    static constexpr int kWordsPerElement = static_cast<int>(sizeof(T)) / 4;
    typedef uint32_t Words __attribute__((vector_size(32)));

    // For each keep mask of a block, the source word of each destination word.
    struct Table {
        uint32_t words[1 << kWidth][8];
    };
    static constexpr Table make_table() {
        Table table{};
        for (int mask = 0; mask < (1 << kWidth); ++mask) {
            int out = 0;
            for (int e = 0; e < kWidth; ++e) {
                if (!(mask >> e & 1)) continue;
                for (int w = 0; w < kWordsPerElement; ++w)
                    table.words[mask][out * kWordsPerElement + w] = static_cast<uint32_t>(e * kWordsPerElement + w);
                ++out;
            }
        }
        return table;
    }
    static constexpr Table kTable = make_table();
};

}  // namespace structmd
