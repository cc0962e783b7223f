#pragma once
// What the kernels that resolve the force field around one chosen particle s ("the seed") share: its
// pair partners within a term's reach, and the bonds it is in with their positions made whole. Used
// by the Hessian (hessian_kernels.hpp) and the pair forces (pair_force_kernels.hpp).
#include "core/box.hpp"
#include "core/hd.hpp"
#include "core/vec.hpp"
#include "forcefield/pair_kernel.hpp"
#include "neighbour/neighbour_view.hpp"

namespace structmd {

// For slot k of the list, when it holds the seed (and the seed is in the group): visit(j, d, p) for
// each neighbour j in the group within the cutoff of their type pair's parameters p (a row of the
// pair table), d = r_j - r_s by minimum image. PairR: the real of the pair distance.
template <class PairR, class R, class Params, class Visit>
SMD_HD SMD_INLINE void for_each_partner_of_seed(const NeighbourView<R>& v, int64_t k, int seed, const uint8_t* group,
                                                const PairTable<Params>& table, Visit&& visit) {
    const int s = v.order[k];
    if (s != seed || (group && !group[s])) return;
    const Real4<R> ps = v.positions[k];
    const Params* row = table.row_of(s, static_cast<int>(ps.w));
    v.for_each_neighbour(static_cast<int>(k), [&](int slot) {
        const int j = v.order[slot];
        const Real4<R> pj = v.positions[slot];
        const Vec3<R> d = v.box.minimum_image(xyz(pj) - xyz(ps));
        const Params& p = row[static_cast<int>(pj.w)];
        if (!(PairR(dot(d, d)) < p.cutoff2) || (group && !group[j])) return;
        visit(j, d, p);
    });
}

// The bonds of N particles of one term, seen from the seed (built by BondIndex::around).
template <int N, class R, class Params>
struct BondsAroundSeed {
    const Real4<R>* pos;
    Box<R> box;
    const int* firstEntry;
    const int* entries;
    const int* members;
    const Params* params;
    int seed;

    // For particle i: visit(params, slot, seedSlot, r) for each bond that holds both i (at `slot`)
    // and the seed (at `seedSlot`), with r[0] the first particle's position and
    // r[m] = r[m-1] + minimum_image(x_m - x_{m-1}), as the bond kernel gives them to the functor.
    template <class Visit>
    SMD_HD SMD_INLINE void for_each_of(int64_t i, Visit&& visit) const {
        for (int k = firstEntry[i]; k < firstEntry[i + 1]; ++k) {
            const int b = entries[k] / N;
            const int* ids = members + N * b;
            int seedSlot = -1;
            for (int m = 0; m < N; ++m)
                if (ids[m] == seed) seedSlot = m;
            if (seedSlot < 0) continue;
            Vec3<R> r[N];
            r[0] = xyz(pos[ids[0]]);
            for (int m = 1; m < N; ++m) r[m] = r[m - 1] + box.minimum_image(xyz(pos[ids[m]]) - xyz(pos[ids[m - 1]]));
            visit(params[b], entries[k] % N, seedSlot, r);
        }
    }
};

}  // namespace structmd
