#pragma once
// Numerical faults found on the backend (a non-finite position, velocity or force) are recorded in
// one device word without stopping the launch or asking the host: the earliest step and, within
// it, the lowest particle index win. The host reads the word at API boundaries.
#include <cmath>
#include <cstdint>

#include "core/atomic.hpp"
#include "core/vec.hpp"

namespace structmd {

constexpr unsigned long long kNoFault = ~0ull;

struct FaultSlot {
    unsigned long long* word;
    int64_t step;

    SMD_HD SMD_INLINE void report(int64_t particle) const {
        atomic_min(word, (static_cast<unsigned long long>(step) << 32) | static_cast<unsigned long long>(particle));
    }
    static int64_t step_of(unsigned long long word) { return static_cast<int64_t>(word >> 32); }
    static int64_t particle_of(unsigned long long word) { return static_cast<int64_t>(word & 0xffffffffull); }
};

template <class R>
SMD_HD SMD_INLINE bool finite(const Real4<R>& a) {
    using std::isfinite;
    return isfinite(a.x) && isfinite(a.y) && isfinite(a.z);
}

}  // namespace structmd
