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

// What a field of per-type parameters reads (external_potential.hpp): each particle takes the
// Params of its type (pos.w) from `table`, in the row of its batch when `batch` is given (a batched
// table, ntypes entries per batch); an entry whose `listed` is 0 acts on nothing.
template <class R, class Params>
struct TypedField {
    const Real4<R>* pos;
    const R* radius;
    const uint8_t* group;
    const Params* table;
    const uint8_t* listed;
    const int* batch;
    int ntypes;
    ClockView now;

    // The table entry that acts on particle i, or null where none does.
    SMD_HD SMD_INLINE const Params* entry_of(int64_t i) const {
        if (group && !group[i]) return nullptr;
        const int at = static_cast<int>(pos[i].w) + (batch ? batch[i] * ntypes : 0);
        return listed[at] ? table + at : nullptr;
    }
};

template <class Potential, class R, bool WantForce, bool WantEnergy>
struct TypedExternalKernel {
    using Params = typename Potential::template Params<R>;
    TypedField<R, Params> field;
    ForceOutputs<R> out;

    SMD_HD void operator()(int64_t i) const {
        const Params* params = field.entry_of(i);
        if (!params) return;
        Vec3<R> f{0, 0, 0};
        const R e = Potential::compute(xyz(field.pos[i]), field.radius[i], *params, R(field.now.time()), f);
        add_to_outputs<WantForce, WantEnergy, false>(out, i, f, e, zero_tensor<R>());
    }
};

}  // namespace structmd
