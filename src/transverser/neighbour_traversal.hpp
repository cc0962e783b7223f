#pragma once
// A transverser (transverser.hpp) over a neighbour list: each particle of the group visits its
// list's neighbours within the cutoff that are in the group, under the list's condition (its
// filter), as a pair term does (forcefield/pair_kernel.hpp). Runs over the list's slots; the
// transverser sees particle indices. Free of the standard library, so that a kernel compiled at run
// time (an expression transverser on CUDA) instantiates this same traversal.
#include "core/hd.hpp"
#include "core/lanes.hpp"
#include "core/vec.hpp"
#include "neighbour/neighbour_view.hpp"
#include "transverser/transverser.hpp"

namespace structmd {

template <class Transverser, class R>
struct NeighbourTraversal {
    Transverser transverser;
    NeighbourView<R> neighbours;
    R cutoff2;             // pairs at r^2 >= cutoff2 are not offered (list candidates reach further)
    const uint8_t* group;  // by particle; null: every particle takes part

    SMD_HD void operator()(int64_t k, Lanes lanes) const {
        const NeighbourView<R>& v = neighbours;
        const int i = v.order[k];
        if (group && !group[i]) return;
        const Transverser& t = transverser;
        const Real4<R> pi = v.positions[k];
        const auto infoI = t.info(i);
        auto total = t.zero();
        v.for_each_neighbour(static_cast<int>(k), [&](int s) {
            const int j = v.order[s];
            const PairFrame<R> pair = pair_frame(pi, v.positions[s], v.box);
            const Vec3<R> d = xyz(pair.second);
            if (!(dot(d, d) < cutoff2) || (group && !group[j])) return;
            t.accumulate(total, t.compute(pair.first, pair.second, infoI, t.info(j)));
        }, lanes);
        total = lanes.combine(total, [&](decltype(total)& a, const decltype(total)& b) { t.accumulate(a, b); });
        if (lanes.leader()) t.set(i, total);
    }
};

}  // namespace structmd
