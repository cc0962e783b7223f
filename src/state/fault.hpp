#pragma once
// Numerical faults found on the backend (a non-finite position, velocity or force) are recorded in
// one device word without stopping the launch or asking the host: the earliest step and, within
// it, the lowest particle index win. The host reads the word at API boundaries.
#include <cmath>
#include <cstdint>

#include "core/atomic.hpp"
#include "core/vec.hpp"
#include "state/step_clock.hpp"

namespace structmd {

constexpr unsigned long long kNoFault = ~0ull;

// mobility: the hydrodynamic mobility matrix could not be factorised (not positive definite).
enum class FaultQuantity : unsigned { position = 0, velocity = 1, force = 2, displacement = 3, mobility = 4 };

template <class R>
SMD_HD SMD_INLINE bool finite(const Real4<R>& a) {
    using std::isfinite;
    return isfinite(a.x) && isfinite(a.y) && isfinite(a.z);
}

// The word holds step << 32 | particle << 3 | quantity, so the smallest is the earliest report.
struct FaultSlot {
    unsigned long long* word;
    ClockView now;
    double maxMove2;  // the square of the longest move allowed in one step (the list skin)

    SMD_HD SMD_INLINE void report(int64_t particle, FaultQuantity quantity) const {
        atomic_min(word, (static_cast<unsigned long long>(now.step()) << 32) |
                             (static_cast<unsigned long long>(particle) << 3) | static_cast<unsigned long long>(quantity));
    }
    template <class R>
    SMD_HD SMD_INLINE void check(int64_t i, const Real4<R>& position, const Real4<R>& force) const {
        if (!finite(position)) report(i, FaultQuantity::position);
        else if (!finite(force)) report(i, FaultQuantity::force);
    }
    template <class R>
    SMD_HD SMD_INLINE void check(int64_t i, const Real4<R>& position, const Real4<R>& velocity,
                                 const Real4<R>& force) const {
        if (!finite(velocity)) report(i, FaultQuantity::velocity);
        else check(i, position, force);
    }
    // A kick's check: it moves no particle, so it has no position to check.
    template <class R>
    SMD_HD SMD_INLINE void check_kick(int64_t i, const Real4<R>& velocity, const Real4<R>& force) const {
        if (!finite(velocity)) report(i, FaultQuantity::velocity);
        else if (!finite(force)) report(i, FaultQuantity::force);
    }
    // A particle that jumps farther than the skin in one step has left the reach of the lists it
    // was counted in: the time step is too large for the forces.
    template <class R>
    SMD_HD SMD_INLINE void check_move(int64_t i, const Vec3<R>& move) const {
        if (static_cast<double>(dot(move, move)) > maxMove2) report(i, FaultQuantity::displacement);
    }

    static int64_t step_of(unsigned long long word) { return static_cast<int64_t>(word >> 32); }
    static int64_t particle_of(unsigned long long word) { return static_cast<int64_t>((word & 0xffffffffull) >> 3); }
    static FaultQuantity quantity_of(unsigned long long word) { return static_cast<FaultQuantity>(word & 7ull); }
};

}  // namespace structmd
