#pragma once
// A neighbour list's copy of this step's positions in its slot order (neighbour/neighbour_view.hpp),
// and the check that decides its rebuild: a particle that moved more than half the skin since it was
// binned raises the flag. Written for every slot each step, by the list itself (RefreshPositions) or
// by the integrator's drift kernel on its way (state/drift_bookkeeping.hpp); it lives with the state
// so that the particles' drift bookkeeping can name it without the state layer reaching up to the
// neighbour lists.
#include "core/atomic.hpp"
#include "core/box.hpp"
#include "state/cell_local_positions.hpp"

namespace structmd {

// Slot of the list's control buffer that holds the rebuild flag (verlet_list_kernels.hpp).
constexpr int kListRebuildFlag = 0;

template <class R>
struct SlotMirror {
    Real4<R>* positions = nullptr;     // this step's, by slot; null: not kept (VerletList::mirror)
    const Real4<R>* binned = nullptr;  // the last build's, by slot; w: its packed cell where cellLocal is kept
    Box<R> box{};
    R halfSkin2 = R(0);
    int* control = nullptr;
    CellLocalPositions<R> cellLocal;  // this step's in float, for a mixed-precision pair kernel

#if !defined(__CUDA_ARCH__) && defined(__GNUC__)
    // Asks the CPU's caches for what record(slot, ...) will touch.
    void prefetch(int64_t slot) const {
        __builtin_prefetch(binned + slot);
        if (positions) __builtin_prefetch(positions + slot, 1);
        if (cellLocal.local) __builtin_prefetch(cellLocal.local + slot, 1);
    }
#endif

    SMD_HD SMD_INLINE void record(int64_t slot, const Real4<R>& p) const {
        if (positions) positions[slot] = p;
        const Real4<R> b = binned[slot];
        const Vec3<R> d = box.minimum_image(xyz(p) - xyz(b));
        if (dot(d, d) > halfSkin2) atomic_max(control + kListRebuildFlag, 1);
        if (cellLocal.local) cellLocal.local[slot] = cellLocal.of(xyz(p), static_cast<float>(b.w), box);
    }
};

}  // namespace structmd
