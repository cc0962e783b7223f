#pragma once
// What the kernels that resolve the force field around one chosen particle s ("the seed") share: its
// pair partners within a term's reach, and the bonds it is in with their positions made whole. Used
// by the Hessian (hessian_kernels.hpp) and the pair forces (pair_force_kernels.hpp).
#include "core/box.hpp"
#include "core/hd.hpp"
#include "core/vec.hpp"
#include "forcefield/bond_kernel.hpp"
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
    const BondEntry<N>* entries;
    const Params* params;
    int seed;

    // For particle i: visit(params, slot, seedSlot, r) for each bond that holds both i (at `slot`)
    // and the seed (at `seedSlot`), with r the bond's positions made whole, as the bond kernel gives
    // them to the functor.
    template <class Visit>
    SMD_HD SMD_INLINE void for_each_of(int64_t i, Visit&& visit) const {
        for (int k = firstEntry[i]; k < firstEntry[i + 1]; ++k) {
            const BondEntry<N> entry = entries[k];
            int seedSlot = -1;
            for (int m = 0; m < N; ++m)
                if (entry.member[m] == seed) seedSlot = m;
            if (seedSlot < 0) continue;
            Vec3<R> r[N];
            bond_positions(pos, box, entry, r);
            visit(params[entry.bondSlot / N], entry.bondSlot % N, seedSlot, r);
        }
    }
};

}  // namespace structmd
