#pragma once
// A transverser (transverser.hpp) over all pairs of particles, without a cutoff (UAMMD's NBody): each
// particle of the group visits every other particle of the group, its periodic image nearest to it
// in a periodic box (an open box: lengths of infinity, where the nearest image is the particle), and
// of its batch (independent systems overlaid in one box, as the neighbour lists keep them apart). The
// cost is n^2, for interactions of no finite range (gravity, unscreened Coulomb in an open box) and
// for systems small enough that a list does not pay. Free of the standard library, as the other
// traversal.
#include "core/box.hpp"
#include "core/hd.hpp"
#include "core/lanes.hpp"
#include "core/vec.hpp"
#include "transverser/transverser.hpp"

namespace structmd {

template <class Transverser, class R>
struct AllPairsTraversal {
    Transverser transverser;
    const Real4<R>* positions;  // by particle (w: the type)
    int64_t count;
    Box<R> box;
    const uint8_t* group;  // by particle; null: every particle takes part
    const int* batch;      // by particle; null: one batch. Particles of different batches never pair

    SMD_HD void operator()(int64_t item, Lanes lanes) const {
        const int i = static_cast<int>(item);
        if (group && !group[i]) return;
        const Transverser& t = transverser;
        const Real4<R> pi = positions[i];
        const auto infoI = t.info(i);
        const int batchI = batch ? batch[i] : 0;
        auto total = t.zero();
        // The lanes take turns through the particles, so each load is shared by a warp's items.
        for (int64_t j = lanes.lane; j < count; j += lanes.count) {
            if (j == item || (group && !group[j]) || (batch && batch[j] != batchI)) continue;
            const PairFrame<R> pair = pair_frame(pi, positions[j], box);
            t.accumulate(total, t.compute(pair.first, pair.second, infoI, t.info(static_cast<int>(j))));
        }
        total = lanes.combine(total, [&](decltype(total)& a, const decltype(total)& b) { t.accumulate(a, b); });
        if (lanes.leader()) t.set(i, total);
    }
};

}  // namespace structmd
