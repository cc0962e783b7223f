#pragma once
// The kernel of a non-bonded pair term over cluster pairs (neighbour/cluster_view.hpp), generic in
// its potential like PairKernel (pair_kernel.hpp), whose potentials, parameter tables and outputs it
// shares. Each cluster sums the forces of all its partners' particles on its own (every pair twice,
// no atomics), in an order fixed by the list, so a run repeats itself bit for bit.
//
// On the GPU a warp takes a cluster: lane = i + 4 j + 16 stream, so each lane holds one particle i
// of the cluster and meets particle j of every other partner cluster (two streams of partners). The
// warp reads 32 list entries in one load and hands them round by shuffles, and each lane loads its
// partner's position whether or not the pair counts, so the loads of several partners are in flight
// at once instead of one list entry, then one position, after the other. The 8 lanes that share an i
// sum their parts through shuffles at the end. With one lane (the CPU) the lane walks all of it.
// Energy and virial of a pair are split equally between the two, as in PairKernel.
#include "core/hd.hpp"
#include "core/lanes.hpp"
#include "core/vec.hpp"
#include "forcefield/force_outputs.hpp"
#include "forcefield/pair_kernel.hpp"
#include "neighbour/cluster_view.hpp"

namespace structmd {

template <class Potential, class R, class PairR, bool WantForce, bool WantEnergy, bool WantVirial>
struct ClusterPairKernel {
    using Params = typename Potential::template Params<PairR>;
    static constexpr int kStreams = 32 / (kClusterSize * kClusterSize);
    const R* charge;
    const R* radius;
    const uint8_t* group;
    ClusterView<R> clusters;
    PairTable<Params> table;
    ForceOutputs<R> out;

    struct Sums {
        Vec3<R> f{R(0), R(0), R(0)};
        R e = R(0);
        Tensor3<R> w = zero_tensor<R>();
    };

    // Adds the pair of slot s (particle i at ri, parameters `row`) and slot t, at pj, to sums
    // where `counts` and the pair lies within its cutoff.
    SMD_HD SMD_INLINE void add_pair(bool counts, int i, const Vec3<R>& ri, const Params* row, int t, const Real4<R>& pj,
                                    Sums& sums) const {
        const ClusterView<R>& v = clusters;
        const Vec3<R> rij = v.box.minimum_image(xyz(pj) - ri);
        const PairR r2 = PairR(dot(rij, rij));
        const Params& p = row[static_cast<int>(pj.w)];
        if (!counts || !(r2 < p.cutoff2) || (group && !group[v.order[t]])) return;
        const PairTerm<PairR> term = evaluate_pair_of<Potential>(r2, p, charge, radius, i, v.order[t]);
        const R dudrOverR = R(term.dudr_over_r);
        if (WantForce) sums.f += dudrOverR * rij;
        if (WantEnergy) sums.e += R(0.5) * R(term.energy);
        if (WantVirial) sums.w += (R(-0.5) * dudrOverR) * outer(rij, rij);
    }

    SMD_HD void operator()(int64_t item, Lanes lanes) const {
        const ClusterView<R>& v = clusters;
        const int c = static_cast<int>(item);
        const int first = v.bounds[2 * c], end = v.bounds[2 * c + 1];
        if (first == end) return;
        if (lanes.count == 32) {
            const int s = first + (lanes.lane % kClusterSize);
            const int offset = (lanes.lane / kClusterSize) % kClusterSize;
            const int stream = lanes.lane / (kClusterSize * kClusterSize);
            const bool mine = s < end;
            const int own = mine ? s : first;  // a slot of the cluster, for the lanes of a missing i
            const int i = v.order[own];
            const bool active = mine && (!group || group[i]);
            const Real4<R> pi = v.positions[own];
            const Vec3<R> ri = xyz(pi);
            const Params* row = table.row_of(i, static_cast<int>(pi.w));
            Sums sums;
            const auto meet = [&](int partnerFirst, int partnerEnd, bool listed) {
                const int t = partnerFirst + offset;
                const bool counts = listed && active && t < partnerEnd && t != s;
                add_pair(counts, i, ri, row, t, v.positions[counts ? t : own], sums);
            };
            if (!v.overflowed(c)) {
                const int n = v.count[c];
                const int* entries = v.entries_of(c);
                for (int base = 0; base < n; base += 32) {
                    const int held = base + lanes.lane < n ? entries[base + lanes.lane] : 0;
                    const int round = n - base < 32 ? n - base : 32;
                    SMD_UNROLL4
                    for (int k = 0; k < round; k += kStreams) {
                        const int entry = lanes.from_lane(held, k + stream);
                        meet(entry_first(entry), entry_end(entry), k + stream < round);
                    }
                }
            } else {
                v.for_each_partner(c, stream, kStreams, [&](int partnerFirst, int partnerEnd) {
                    meet(partnerFirst, partnerEnd, true);
                });
            }
            constexpr int kShare = kClusterSize;  // lanes of one i are kClusterSize apart
            if (WantForce) sums.f = lanes.sum_across(sums.f, kShare);
            if (WantEnergy) sums.e = lanes.sum_across(sums.e, kShare);
            if (WantVirial) sums.w = lanes.sum_across(sums.w, kShare);
            if (active && lanes.lane < kClusterSize) add_to_outputs<WantForce, WantEnergy, WantVirial>(out, i, sums.f, sums.e, sums.w);
            return;
        }
        for (int s = first; s < end; ++s) {
            const int i = v.order[s];
            if (group && !group[i]) continue;
            const Real4<R> pi = v.positions[s];
            const Params* row = table.row_of(i, static_cast<int>(pi.w));
            Sums sums;
            v.for_each_partner(c, 0, 1, [&](int partnerFirst, int partnerEnd) {
                for (int t = partnerFirst; t < partnerEnd; ++t) add_pair(t != s, i, xyz(pi), row, t, v.positions[t], sums);
            });
            add_to_outputs<WantForce, WantEnergy, WantVirial>(out, i, sums.f, sums.e, sums.w);
        }
    }
};

}  // namespace structmd
