#pragma once
// Functors of the Verlet list build. Each runs on both backends; every one after the displacement
// check returns at once unless the device-side rebuild flag is set, so deciding whether to rebuild
// needs no trip to the host.
#include <cstdint>

#include "core/atomic.hpp"
#include "core/vec.hpp"
#include "neighbour/neighbour_view.hpp"

namespace structmd {

// Slots of the list's small control buffer.
enum ListControl : int {
    kRebuild = 0,        // 1 while a rebuild is under way this step
    kBuilds = 1,         // number of builds since load
    kMaxCellFill = 2,    // the fullest cell seen at a build
    kMaxNeighbours = 3,  // the longest list seen at a build
    kControlSlots = 4
};

template <class R>
struct CheckDisplacement {
    const Real4<R>* pos;
    const Real4<R>* reference;
    Box<R> box;
    R halfSkin2;
    int* control;
    SMD_HD void operator()(int64_t i) const {
        const Vec3<R> d = box.minimum_image(xyz(pos[i]) - xyz(reference[i]));
        if (dot(d, d) > halfSkin2) atomic_max(control + kRebuild, 1);
    }
};

struct ClearCells {
    int* control;
    int* cellCount;
    int* overflowCount;
    SMD_HD void operator()(int64_t c) const {
        if (!control[kRebuild]) return;
        cellCount[c] = 0;
        if (c == 0) {
            *overflowCount = 0;
            control[kBuilds] += 1;
        }
    }
};

template <class R>
struct BinParticles {
    const Real4<R>* pos;
    Real4<R>* reference;
    NeighbourView<R> view;
    int* control;
    SMD_HD void operator()(int64_t i) const {
        if (!control[kRebuild]) return;
        const Real4<R> p = pos[i];
        reference[i] = p;
        int cx, cy, cz;
        view.grid.coordinates(xyz(p), view.box, cx, cy, cz);
        const int c = view.grid.index(cx, cy, cz);
        const int slot = atomic_add(view.cellCount + c, 1);
        if (slot < view.cellCapacity)
            view.cellParticles[static_cast<int64_t>(c) * view.cellCapacity + slot] = static_cast<int>(i);
        else
            view.overflow[atomic_add(view.overflowCount, 1)] = static_cast<int>(i);
        atomic_max(control + kMaxCellFill, slot + 1);
    }
};

SMD_HD SMD_INLINE void insertion_sort(int* a, int n) {
    for (int k = 1; k < n; ++k) {
        const int v = a[k];
        int m = k - 1;
        while (m >= 0 && a[m] > v) {
            a[m + 1] = a[m];
            --m;
        }
        a[m + 1] = v;
    }
}

// Binning order depends on thread timing; sorting each cell makes the lists, and so the order of
// force sums, the same on every run and every thread count. Each cell then keeps a copy of its
// members' positions beside their indices, so the list build reads candidates contiguously
// instead of gathering them from all over the position array.
template <class R>
struct SortCells {
    const Real4<R>* pos;
    NeighbourView<R> view;
    int* control;
    SMD_HD void operator()(int64_t c) const {
        if (!control[kRebuild]) return;
        const int m = view.cellCount[c] < view.cellCapacity ? view.cellCount[c] : view.cellCapacity;
        int* members = view.cellParticles + c * view.cellCapacity;
        insertion_sort(members, m);
        Real4<R>* positions = view.cellPositions + c * view.cellCapacity;
        for (int s = 0; s < m; ++s) positions[s] = pos[members[s]];
        if (c == 0) insertion_sort(view.overflow, *view.overflowCount);
    }
};

// Each particle's lanes take the candidates of a cell in rounds, one candidate per lane, and append
// those within the list radius in lane order: the list comes out in cell order, independent of
// thread timing.
template <class R>
struct BuildLists {
    const Real4<R>* pos;
    NeighbourView<R> view;
    R listRadius2;
    int* control;
    bool ordered;  // sort each list by index (see below)

    SMD_HD void operator()(int64_t i, Lanes lanes) const {
        if (!control[kRebuild]) return;
        const NeighbourView<R>& v = view;
        const Vec3<R> ri = xyz(pos[i]);
        int* entries = v.entries_of(i);
        int n = 0;
        const auto consider = [&](bool exists, int j, const Real4<R>& pj) {
            bool accepted = false;
            if (exists && j != i && v.filter.accepts(static_cast<int>(i), j)) {
                const Vec3<R> d = v.box.minimum_image(xyz(pj) - ri);
                accepted = dot(d, d) < listRadius2;
            }
            int found = 0;
            const int slot = n + lanes.rank_among(accepted, found);
            if (accepted && slot < v.capacity) entries[slot * v.entryStride] = j;
            n += found;
        };
        int cx, cy, cz;
        v.grid.coordinates(ri, v.box, cx, cy, cz);
        v.grid.for_each_adjacent(cx, cy, cz, [&](int c) {
            const int m = v.cellCount[c] < v.cellCapacity ? v.cellCount[c] : v.cellCapacity;
            const int64_t first = static_cast<int64_t>(c) * v.cellCapacity;
            for (int base = 0; base < m; base += lanes.count) {
                const int s = base + lanes.lane;
                const bool exists = s < m;
                consider(exists, exists ? v.cellParticles[first + s] : -1,
                         exists ? v.cellPositions[first + s] : Real4<R>{});
            }
        });
        const int extra = *v.overflowCount;
        for (int base = 0; base < extra; base += lanes.count) {
            const int k = base + lanes.lane;
            const bool exists = k < extra;
            const int j = exists ? v.overflow[k] : -1;
            consider(exists, j, exists ? pos[j] : Real4<R>{});
        }
        if (!lanes.leader()) return;
        // In index order, so a particle's force sum does not depend on which cells the particles
        // happened to occupy at this build: a restarted run repeats the same sums bit for bit.
        const int stored = !ordered ? 0 : (n < v.capacity ? n : v.capacity);
        for (int k = 1; k < stored; ++k) {
            const int value = entries[k * v.entryStride];
            int m = k - 1;
            while (m >= 0 && entries[m * v.entryStride] > value) {
                entries[(m + 1) * v.entryStride] = entries[m * v.entryStride];
                --m;
            }
            entries[(m + 1) * v.entryStride] = value;
        }
        v.count[i] = n;
        atomic_max(control + kMaxNeighbours, n);
    }
};

}  // namespace structmd
