#pragma once
// Which pairs a neighbour list may hold: a list's condition keeps excluded pairs out (nonExcluded)
// or pairs within or across models (intra, inter). Applied when the list is built and on the
// cell-scan fallback, never per force evaluation. (Pairs in different batches never meet: each
// batch has cells of its own, cell_grid.hpp.)
#include "core/hd.hpp"

namespace structmd {

enum class PairCondition : int { all, nonExcluded, intra, inter };

struct PairFilter {
    PairCondition condition = PairCondition::all;
    const int* model = nullptr;  // for intra / inter
    const int* excludedStart = nullptr;  // nonExcluded: sorted ids excluded for i in
    const int* excluded = nullptr;       // excluded[excludedStart[i] .. excludedStart[i+1])

    // Whether every pair is accepted, so a caller need not look up which particles it has.
    SMD_HD SMD_INLINE bool trivial() const { return condition == PairCondition::all; }

    SMD_HD SMD_INLINE bool accepts(int i, int j) const {
        switch (condition) {
            case PairCondition::all: return true;
            case PairCondition::intra: return model[i] == model[j];
            case PairCondition::inter: return model[i] != model[j];
            case PairCondition::nonExcluded: {
                int lo = excludedStart[i], hi = excludedStart[i + 1];
                while (lo < hi) {
                    const int mid = (lo + hi) / 2;
                    if (excluded[mid] < j) lo = mid + 1;
                    else hi = mid;
                }
                return !(lo < excludedStart[i + 1] && excluded[lo] == j);
            }
        }
        return true;
    }
};

}  // namespace structmd
