#pragma once
// Which pairs a neighbour list may hold: a list's condition keeps excluded pairs out (the lists of
// exclusions) and picks pairs within or across models, between charged particles, between types or
// groups of types. Applied when the list is built and on the cell-scan fallback, never per force
// evaluation. (Pairs in different batches never meet: each batch has cells of its own,
// cell_grid.hpp.)

#include "core/hd.hpp"

#if SMD_HOST_CODE
#include <cstdint>  // NVRTC takes the fixed-width integers from core/hd.hpp
#endif

namespace structmd {

// The sub-lists UAMMD-structured's VerletConditionalListSet entries offer, each a predicate on a pair
// of non-excluded particles.
enum class PairCondition : int {
    all,
    intra,                   // same model
    inter,                   // different models
    charged,                 // both charged
    interCharged,            // different models, both charged
    interDifferentType,      // different models and different types
    typeGroup1Intra,         // same model, both of type group 1
    typeGroup2Intra,         // same model, both of type group 2
    typeGroupsInter,         // both in a type group, and different models or different groups
    noTypeGroup,             // at least one in neither type group
};

struct PairFilter {
    PairCondition condition = PairCondition::all;
    const int* model = nullptr;          // by particle, for the conditions on models
    const int* excludedStart = nullptr;  // null: no exclusions; else the sorted ids excluded for i are
    const int* excluded = nullptr;       // excluded[excludedStart[i] .. excludedStart[i+1])
    const int* kind = nullptr;           // by particle: its type, or its type group (0: none, 1, 2)
    const uint8_t* charged = nullptr;    // by particle: 1 where its charge is not zero

    // Whether every pair is accepted, so a caller need not look up which particles it has.
    SMD_HD SMD_INLINE bool trivial() const { return condition == PairCondition::all && !excludedStart; }

    SMD_HD SMD_INLINE bool accepts(int i, int j) const { return !(excludedStart && is_excluded(i, j)) && meets_condition(i, j); }

    // A particle's exclusions held in registers where it has few (a bead of a chain has two to four),
    // so that a list build, which tests the same particle against each of its candidates, compares
    // instead of searching memory for every one.
    struct FewExclusions {
        static constexpr int kMost = 4;
        int id[kMost] = {-1, -1, -1, -1};  // the exclusions, the places past them -1 (no particle)
        bool many = false;                  // more than kMost: accepts() searches the list
    };
    SMD_HD SMD_INLINE FewExclusions few_exclusions_of(int i) const {
        FewExclusions few;
        if (!excludedStart) return few;
        const int first = excludedStart[i], count = excludedStart[i + 1] - first;
        few.many = count > FewExclusions::kMost;
        if (!few.many)
            for (int m = 0; m < count; ++m) few.id[m] = excluded[first + m];
        return few;
    }
    // accepts(i, j) for the i whose exclusions `few` holds.
    SMD_HD SMD_INLINE bool accepts(int i, int j, const FewExclusions& few) const {
        const bool excluded = few.many ? is_excluded(i, j)
                                       : (j == few.id[0]) | (j == few.id[1]) | (j == few.id[2]) | (j == few.id[3]);
        return !excluded && meets_condition(i, j);
    }

private:
    SMD_HD SMD_INLINE bool meets_condition(int i, int j) const {
        switch (condition) {
            case PairCondition::all: return true;
            case PairCondition::intra: return model[i] == model[j];
            case PairCondition::inter: return model[i] != model[j];
            case PairCondition::charged: return charged[i] && charged[j];
            case PairCondition::interCharged: return model[i] != model[j] && charged[i] && charged[j];
            case PairCondition::interDifferentType: return model[i] != model[j] && kind[i] != kind[j];
            case PairCondition::typeGroup1Intra: return model[i] == model[j] && kind[i] == 1 && kind[j] == 1;
            case PairCondition::typeGroup2Intra: return model[i] == model[j] && kind[i] == 2 && kind[j] == 2;
            case PairCondition::typeGroupsInter:
                return kind[i] != 0 && kind[j] != 0 && (model[i] != model[j] || kind[i] != kind[j]);
            case PairCondition::noTypeGroup: return kind[i] == 0 || kind[j] == 0;
        }
        return true;
    }

    SMD_HD SMD_INLINE bool is_excluded(int i, int j) const {
        int lo = excludedStart[i], hi = excludedStart[i + 1];
        while (lo < hi) {
            const int mid = (lo + hi) / 2;
            if (excluded[mid] < j) lo = mid + 1;
            else hi = mid;
        }
        return lo < excludedStart[i + 1] && excluded[lo] == j;
    }
};

}  // namespace structmd
