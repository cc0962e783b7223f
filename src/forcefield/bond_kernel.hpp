#pragma once
// The kernel of a bonded term of N = 1..4 particles, generic in its potential. Each particle visits
// the bonds it takes part in and keeps its own share: no atomics, and the same sum order on every
// backend. Energy and virial of a bond are split equally among its N particles; the virial of a
// bond is sum_k d_k (x) F_k with d_k the position of particle k relative to the first. Free of the
// standard library, so that kernels compiled at run time (an expression bond on CUDA) instantiate
// this same traversal.
#include "core/box.hpp"
#include "core/hd.hpp"
#include "core/vec.hpp"
#include "forcefield/force_outputs.hpp"

namespace structmd {

// A particle's place in one bond, as the kernels read it: the bond and the particle's slot in it,
// packed as bond * N + slot (the bond picks the parameters), then the bond's N particles. One
// aligned record, so an entry is one vector load and the positions wait on nothing else; an index
// into the bonds' members made them wait on two loads, one after the other.
template <int N>
struct alignas(N == 1 ? 8 : N <= 3 ? 16 : 32) BondEntry {
    int bondSlot;
    int member[N];
};

// The positions of an entry's bond made whole: r[0] the first particle's, and
// r[m] = r[m-1] + minimum_image(x_m - x_{m-1}).
template <int N, class R>
SMD_HD SMD_INLINE void bond_positions(const Real4<R>* pos, const Box<R>& box, const BondEntry<N>& entry, Vec3<R>* r) {
    r[0] = xyz(pos[entry.member[0]]);
    for (int m = 1; m < N; ++m)
        r[m] = r[m - 1] + box.minimum_image(xyz(pos[entry.member[m]]) - xyz(pos[entry.member[m - 1]]));
}

template <class Potential, class R, bool WantForce, bool WantEnergy, bool WantVirial>
struct BondKernel {
    static constexpr int N = Potential::arity;
    using Params = typename Potential::template Params<R>;
    const Real4<R>* pos;
    Box<R> box;
    const int* firstEntry;  // entries of particle i: entries[firstEntry[i] .. firstEntry[i+1])
    const BondEntry<N>* entries;
    const Params* params;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t i) const {
        Vec3<R> f{0, 0, 0};
        R e = 0;
        Tensor3<R> w = zero_tensor<R>();
        const int first = firstEntry[i], last = firstEntry[i + 1];
        // N entries at a time (as many as an inner particle of a linear chain has): all their
        // records, then all their positions, loaded before any is used, so the loads of a round
        // overlap. A round past the last entry repeats it and leaves it out of the sums.
        for (int round = first; round < last; round += N) {
            BondEntry<N> entry[N];
            SMD_UNROLL
            for (int g = 0; g < N; ++g) entry[g] = entries[round + g < last ? round + g : last - 1];
            Vec3<R> r[N][N];
            SMD_UNROLL
            for (int g = 0; g < N; ++g) bond_positions(pos, box, entry[g], r[g]);
            SMD_UNROLL
            for (int g = 0; g < N; ++g) {
                if (round + g >= last) break;
                const int b = entry[g].bondSlot / N;
                Vec3<R> force[N];
                const R energy = Potential::compute(r[g], params[b], box, force);
                if (WantForce) f += force[entry[g].bondSlot % N];
                if (WantEnergy) e += energy / R(N);
                if (WantVirial)
                    for (int m = 1; m < N; ++m) w += (R(1) / R(N)) * outer(r[g][m] - r[g][0], force[m]);
            }
        }
        add_to_outputs<WantForce, WantEnergy, WantVirial>(out, i, f, e, w);
    }
};

}  // namespace structmd
