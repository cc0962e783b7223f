#pragma once
// Where an interaction term adds its contributions: per-particle forces, energies, virials and
// torques (lab frame; only terms acting on orientations add to them), each a null pointer when not
// wanted. Kept free of the standard library: kernels compiled at run time include it (core/hd.hpp).
#include "core/hd.hpp"
#include "core/vec.hpp"

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
};

// Adds one particle's sums to the requested outputs; each particle is written by one thread only.
template <bool WantForce, bool WantEnergy, bool WantVirial, class R>
SMD_HD SMD_INLINE void add_to_outputs(const ForceOutputs<R>& out, int64_t i, const Vec3<R>& f, R e,
                                      const Tensor3<R>& w) {
    if (WantForce) {
        Real4<R>& fi = out.force[i];
        fi.x += f.x;
        fi.y += f.y;
        fi.z += f.z;
    }
    if (WantEnergy) out.energy[i] += e;
    if (WantVirial) out.virial[i] += w;
}

}  // namespace structmd
