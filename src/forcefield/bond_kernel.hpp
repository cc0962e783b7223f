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

template <class Potential, class R, bool WantForce, bool WantEnergy, bool WantVirial>
struct BondKernel {
    static constexpr int N = Potential::arity;
    using Params = typename Potential::template Params<R>;
    const Real4<R>* pos;
    Box<R> box;
    const int* firstEntry;  // entries of particle i: entries[firstEntry[i] .. firstEntry[i+1])
    const int* entries;     // bond * N + the particle's slot in that bond
    const int* members;     // particles of bond b: members[N b .. N b + N)
    const Params* params;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t i) const {
        Vec3<R> f{0, 0, 0};
        R e = 0;
        Tensor3<R> w = zero_tensor<R>();
        for (int k = firstEntry[i]; k < firstEntry[i + 1]; ++k) {
            const int b = entries[k] / N;
            const int slot = entries[k] % N;
            const int* ids = members + N * b;
            Vec3<R> r[N];
            r[0] = xyz(pos[ids[0]]);
            for (int m = 1; m < N; ++m)
                r[m] = r[m - 1] + box.minimum_image(xyz(pos[ids[m]]) - xyz(pos[ids[m - 1]]));
            Vec3<R> force[N];
            const R energy = Potential::compute(r, params[b], box, force);
            if (WantForce) f += force[slot];
            if (WantEnergy) e += energy / R(N);
            if (WantVirial)
                for (int m = 1; m < N; ++m) w += (R(1) / R(N)) * outer(r[m] - r[0], force[m]);
        }
        add_to_outputs<WantForce, WantEnergy, WantVirial>(out, i, f, e, w);
    }
};

}  // namespace structmd
