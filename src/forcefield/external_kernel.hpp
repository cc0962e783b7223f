#pragma once
// The kernel of a field acting on each particle alone, generic in its potential: it adds force and
// energy, no virial (an external field has no pair partner). Free of the standard library, so that
// kernels compiled at run time (an expression field on CUDA) instantiate this same kernel.
#include "core/hd.hpp"
#include "core/vec.hpp"
#include "forcefield/force_outputs.hpp"
#include "state/step_clock.hpp"

namespace structmd {

template <class Potential, class R, bool WantForce, bool WantEnergy, bool WantVirial>
struct ExternalKernel {
    using Params = typename Potential::template Params<R>;
    const Real4<R>* pos;
    const R* radius;
    const uint8_t* group;
    Params params;
    ClockView now;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t i) const {
        if (group && !group[i]) return;
        Vec3<R> f{0, 0, 0};
        const R e = Potential::compute(xyz(pos[i]), radius[i], params, R(now.time()), f);
        add_to_outputs<WantForce, WantEnergy, false>(out, i, f, e, zero_tensor<R>());
    }
};

// The entry of particle i (position p) in a per-type table: its type, in the row of its batch when
// `batch` is given (ntypes entries per batch).
template <class R>
SMD_HD SMD_INLINE int typed_entry(const Real4<R>& p, const int* batch, int64_t i, int ntypes) {
    return static_cast<int>(p.w) + (batch ? batch[i] * ntypes : 0);
}

// The same for a potential of per-type parameters (external_potential.hpp): each particle takes the
// Params of its type (pos.w) from `table`, in the row of its batch when `batch` is given (a batched
// table, ntypes entries per batch); an entry whose `listed` is 0 acts on nothing.
template <class Potential, class R, bool WantForce, bool WantEnergy>
struct TypedExternalKernel {
    using Params = typename Potential::template Params<R>;
    const Real4<R>* pos;
    const R* radius;
    const uint8_t* group;
    const Params* table;
    const uint8_t* listed;
    const int* batch;
    int ntypes;
    ClockView now;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t i) const {
        if (group && !group[i]) return;
        const Real4<R> p = pos[i];
        const int at = typed_entry(p, batch, i, ntypes);
        if (!listed[at]) return;
        Vec3<R> f{0, 0, 0};
        const R e = Potential::compute(xyz(p), radius[i], table[at], R(now.time()), f);
        add_to_outputs<WantForce, WantEnergy, false>(out, i, f, e, zero_tensor<R>());
    }
};

}  // namespace structmd
