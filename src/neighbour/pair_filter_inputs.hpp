#pragma once
// What a list's PairFilter reads about each particle, as the reader gives it (host side; the list
// uploads what its condition needs).
#include <cstdint>
#include <vector>

namespace structmd {

struct PairFilterInputs {
    std::vector<std::vector<int>> excluded;  // by particle id, the sorted ids it never pairs with; empty: no exclusions
    std::vector<int> kind;                   // by particle: type or type group, for the conditions that read one
    std::vector<uint8_t> charged;            // by particle: 1 where charged, for the charged conditions
};

}  // namespace structmd
