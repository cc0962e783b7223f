#pragma once
// Work of the force evaluation that follows a drift, done by the drift kernel on its way through
// the particles: clearing the forces (to the host's external ones) and the first neighbour list's
// position copy and displacement check (state/slot_mirror.hpp). Each is a pass over the
// particles and a dependent kernel less per step; in a small system the step is that chain of
// kernels. The engine fills it after each force update (null members: nothing to take over), and an
// integrator whose drift applies it to every particle, moved or not, reports so with
// positions_moved (integrators/integrator.hpp).
#include "core/vec.hpp"
#include "state/slot_mirror.hpp"

namespace structmd {

template <class R>
struct DriftBookkeeping {
    Real4<R>* force = nullptr;            // cleared when given
    const Real4<R>* external = nullptr;   // what the forces are cleared to; null: zero
    const int* slotOf = nullptr;          // the mirrored list's slot of each particle; null: none
    int64_t slots = 0;                    // the length of slotOf
    SlotMirror<R> mirror;

    // Particle i, at its position after the drift.
    SMD_HD SMD_INLINE void operator()(int64_t i, const Real4<R>& position) const {
        if (force) force[i] = external ? external[i] : Real4<R>{R(0), R(0), R(0), R(0)};
        if (slotOf) {
#if !defined(__CUDA_ARCH__) && defined(__GNUC__)
            // On the CPU the particles come in turn and their slots in cell order: the mirror's
            // reads miss the cache, a particle at a time, unless asked for some particles ahead.
            constexpr int64_t kAhead = 16;
            if (i + kAhead < slots) mirror.prefetch(slotOf[i + kAhead]);
#endif
            mirror.record(slotOf[i], position);
        }
    }
};

}  // namespace structmd
