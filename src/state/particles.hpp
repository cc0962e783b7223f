#pragma once
// Particle data resident on the backend, as structure of arrays. Internal index i is particle id i;
// host transfers go through the engine's getters and setters only, so a later reordering (along a
// space-filling curve) changes nothing outside the engine.
#include <cstdint>

#include "core/box.hpp"
#include "core/noise_key.hpp"
#include "core/state_columns.hpp"
#include "core/vec.hpp"
#include "state/drift_bookkeeping.hpp"
#include "state/fault.hpp"
#include "state/timeline.hpp"

namespace structmd {

template <class B, class R>
struct Particles {
    template <class T>
    using Buffer = typename B::template Buffer<T>;

    int64_t count = 0;
    Box<R> box{};
    Buffer<Real4<R>> pos;    // w: type index
    Buffer<Image> image;     // box crossings since the position was set: unwrapped = pos + image L
    Buffer<Real4<R>> vel;    // w: mass
    Buffer<Real4<R>> force;  // w: unused
    Buffer<R> energy;        // per-particle potential energy, sized when first asked for
    Buffer<Tensor3<R>> virial;
    Buffer<Real4<R>> externalForce;  // empty when the host set none
    Buffer<R> radius;
    Buffer<R> charge;
    Buffer<int> batch;  // batchId by particle; empty when every particle is in batch 0
    Buffer<int> batchIndex;  // the same batches numbered 0, 1, ... in order of batchId; empty with batch
    Buffer<int> model;  // modelId by particle
    Buffer<unsigned long long> fault;  // one word, kNoFault when all is well
    Buffer<StepClock> clock;           // one entry: the step and time on the backend
    Buffer<double> lambda;             // one entry: the ensemble's coupling parameter, in [0, 1]
    Timeline timeline;                 // the step and time, as the host knows them
    int64_t version = 0;               // changes whenever positions or the box change
    DriftBookkeeping<R> drift;         // what the next drift kernel may do for the engine
    NoiseKey noise;                    // the seed and the global id of slot 0, for counter-based noise

    ClockView now() const { return timeline.view(clock.data()); }
    double maxMove2 = 1e300;           // see FaultSlot; no limit without neighbour lists
    // ahead = 1 in kernels that produce the next step's state before the engine moves on to it: a
    // fault is reported at the step whose state went wrong.
    FaultSlot fault_slot(int64_t ahead = 0) {
        ClockView view = now();
        view.stepOffset += ahead;
        return {fault.data(), view, maxMove2};
    }

    // Orientations, last so that terms built against the earlier layout read the rest unchanged.
    // dir: unit quaternions (x: the scalar part q0; y, z, w: q1, q2, q3, UAMMD-structured's order),
    // empty unless the input gives directions, an integrator rotates or the host set them.
    Buffer<Real4<R>> dir;
    Buffer<Real4<R>> torque;            // lab frame, w unused; empty until an integrator or the host reads torques

    // Magnetic moments, after the orientations for the same reason; each empty unless the input gives
    // the state's magnetization. xyz: the moment's unit direction in the body frame (UAMMD-structured's
    // layout: the moment turns with the particle), w: its magnitude M.
    Buffer<Real4<R>> magnetization;
    Buffer<Real4<R>> magneticField;  // lab frame, w unused; sized when a magnetic integrator asks for fields

    // The state's optional columns (core/state_columns.hpp), those read by kernels; each empty when
    // not given.
    PerStateColumn<Buffer<R>> columns;
};

}  // namespace structmd
