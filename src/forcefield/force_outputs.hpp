#pragma once
// Where an interaction term adds its contributions: per-particle forces, energies, virials and
// torques (lab frame; only terms acting on orientations add to them), each a null pointer when not
// wanted. Kept free of the standard library: kernels compiled at run time include it (core/hd.hpp).
#include "core/hd.hpp"
#include "core/vec.hpp"

#if SMD_HOST_CODE
#include <type_traits>
#endif

namespace structmd {

template <class R>
struct ForceOutputs {
    Real4<R>* force = nullptr;
    R* energy = nullptr;
    Tensor3<R>* virial = nullptr;
    Real4<R>* torque = nullptr;  // after the others: a term built against the earlier layout still reads them
    // The magnetic field B at each particle (lab frame) from the terms that make one (["External",
    // "ConstantMagneticField"], dipoles), asked for alone by the magnetic integrators.
    Real4<R>* magneticField = nullptr;
    // Set for the first term of a force evaluation whose kernels write every particle's force once
    // (Interactor::stores_forces): it stores forceBase[i] (zero where null) plus its own rather than
    // adding to a buffer cleared first, which saves a pass that writes the forces and a read of them.
    // A word rather than a bool: no padding, since kernel arguments are compared byte by byte
    // (backends/cuda/step_graphs.cuh).
    const Real4<R>* forceBase = nullptr;
    long long storeForce = 0;
};

// Outputs that take each particle's energy alone (a dU/dlambda, an energy probe).
template <class R>
SMD_HD SMD_INLINE ForceOutputs<R> energy_outputs(R* perParticle) {
    ForceOutputs<R> out;
    out.energy = perParticle;
    return out;
}

// to.xyz += v; w stays.
template <class R>
SMD_HD SMD_INLINE void accumulate(Real4<R>& to, const Vec3<R>& v) {
    to.x += v.x;
    to.y += v.y;
    to.z += v.z;
}

// Adds one particle's sums to the requested outputs; each particle is written by one thread only.
template <bool WantForce, bool WantEnergy, bool WantVirial, class R>
SMD_HD SMD_INLINE void add_to_outputs(const ForceOutputs<R>& out, int64_t i, const Vec3<R>& f, R e,
                                      const Tensor3<R>& w) {
    if (WantForce) {
        if (out.storeForce) {
            // the sums InitForces and accumulate would have made
            const Real4<R> base = out.forceBase ? out.forceBase[i] : Real4<R>{R(0), R(0), R(0), R(0)};
            out.force[i] = Real4<R>{base.x + f.x, base.y + f.y, base.z + f.z, base.w};
        } else {
            accumulate(out.force[i], f);
        }
    }
    if (WantEnergy) out.energy[i] += e;
    if (WantVirial) out.virial[i] += w;
}

// The same for a term that also turns the particle: its torque t goes with the force, where
// torques are asked for.
template <bool WantForce, bool WantEnergy, bool WantVirial, class R>
SMD_HD SMD_INLINE void add_to_outputs(const ForceOutputs<R>& out, int64_t i, const Vec3<R>& f, R e,
                                      const Tensor3<R>& w, const Vec3<R>& t) {
    add_to_outputs<WantForce, WantEnergy, WantVirial>(out, i, f, e, w);
    if (WantForce && out.torque) accumulate(out.torque[i], t);
}

#if SMD_HOST_CODE
// Calls launch(want_force, want_energy, want_virial) with std::bool_constant arguments for the
// outputs asked for, so that a kernel is instantiated with the unwanted ones compiled out; nothing
// where none is asked for.
template <class Launch>
void dispatch_wanted(bool force, bool energy, bool virial, Launch&& launch) {
    using T = std::true_type;
    using F = std::false_type;
    switch ((force ? 1 : 0) | (energy ? 2 : 0) | (virial ? 4 : 0)) {
        case 1: launch(T{}, F{}, F{}); break;
        case 2: launch(F{}, T{}, F{}); break;
        case 3: launch(T{}, T{}, F{}); break;
        case 4: launch(F{}, F{}, T{}); break;
        case 5: launch(T{}, F{}, T{}); break;
        case 6: launch(F{}, T{}, T{}); break;
        case 7: launch(T{}, T{}, T{}); break;
        default: break;
    }
}
#endif

}  // namespace structmd
