#pragma once
// Small per-particle functors of the engine: clearing forces and the sums behind energies and the
// virial. Sums are taken in double whatever the working precision.
#include <cstdint>

#include "core/box.hpp"
#include "core/vec.hpp"
#include "state/fault.hpp"

namespace structmd {

template <class R>
struct InitForces {
    Real4<R>* force;
    const Real4<R>* external;  // null when the host set no external forces
    SMD_HD void operator()(int64_t i) const {
        force[i] = external ? external[i] : Real4<R>{R(0), R(0), R(0), R(0)};
    }
};

// 1 for a particle whose force is not finite: summed, it checks the forces without copying them.
template <class R>
struct NonFiniteForce {
    const Real4<R>* force;
    SMD_HD double operator()(int64_t i) const { return finite(force[i]) ? 0.0 : 1.0; }
};

template <class R>
struct SumEnergy {
    const R* energy;
    SMD_HD double operator()(int64_t i) const { return static_cast<double>(energy[i]); }
};

template <class R>
struct KineticEnergy {
    const Real4<R>* vel;
    SMD_HD double operator()(int64_t i) const {
        const Real4<R> v = vel[i];
        return 0.5 * static_cast<double>(v.w) *
               (static_cast<double>(v.x) * v.x + static_cast<double>(v.y) * v.y + static_cast<double>(v.z) * v.z);
    }
};

template <class R>
struct SumVirial {
    const Tensor3<R>* virial;
    SMD_HD Tensor3<double> operator()(int64_t i) const {
        const Tensor3<R>& w = virial[i];
        return {w.xx, w.xy, w.xz, w.yx, w.yy, w.yz, w.zx, w.zy, w.zz};
    }
};

// A per-particle sum restricted to the particles of one batch.
template <class Sum>
struct InBatch {
    Sum sum;
    const int* batch;
    int wanted;
    SMD_HD double operator()(int64_t i) const { return batch[i] == wanted ? sum(i) : 0.0; }
};

// A subset of particles by id, between a backend array of every particle and a packed array of m
// entries in the order of ids: the host exchanges m entries, not the whole array.
template <class T>
struct GatherById {
    const T* from;  // by particle
    const int64_t* ids;
    T* to;  // m entries
    SMD_HD void operator()(int64_t k) const { to[k] = from[ids[k]]; }
};

// GatherById of positions that also copies the fault word (one word, by the first thread): the
// watched region and the step call's fault flag come back in one kernel.
template <class R>
struct GatherWithFaultWord {
    const Real4<R>* from;  // by particle
    const int64_t* ids;
    Real4<R>* to;  // m entries
    const unsigned long long* fault;
    unsigned long long* faultCopy;
    SMD_HD void operator()(int64_t k) const {
        to[k] = from[ids[k]];
        if (k == 0) *faultCopy = *fault;
    }
};

template <class T>
struct ScatterById {
    const T* from;  // m entries
    const int64_t* ids;  // distinct
    T* to;  // by particle
    SMD_HD void operator()(int64_t k) const { to[ids[k]] = from[k]; }
};

template <class T>
struct CopyArray {
    const T* from;
    T* to;
    SMD_HD void operator()(int64_t i) const { to[i] = from[i]; }
};

// The squared distance (minimum image) slot i moved from where it was.
template <class R>
struct SquaredMoveSince {
    const Real4<R>* pos;
    const Real4<R>* was;
    Box<R> box;
    SMD_HD R operator()(int64_t i) const {
        const Vec3<R> d = box.minimum_image(
            Vec3<R>{pos[i].x - was[i].x, pos[i].y - was[i].y, pos[i].z - was[i].z});
        return d.x * d.x + d.y * d.y + d.z * d.z;
    }
};

// Replaces the host's external force on some particles (ids, or every particle when null) with
// values (zero when null). Where the forces are current (force not null) they change by the same
// difference, so a host that sets its field every step costs no new force evaluation.
template <class R>
struct ReplaceExternalForces {
    const int64_t* ids;
    const Real4<R>* values;
    Real4<R>* external;
    Real4<R>* force;
    SMD_HD void operator()(int64_t k) const {
        const int64_t i = ids ? ids[k] : k;
        const Real4<R> now = values ? values[k] : Real4<R>{R(0), R(0), R(0), R(0)};
        if (force) {
            Real4<R>& f = force[i];
            f.x += now.x - external[i].x;
            f.y += now.y - external[i].y;
            f.z += now.z - external[i].z;
        }
        external[i] = now;
    }
};

// Copies the dynamical state (positions, images, velocities) from one set of buffers to another:
// the engine keeps the state a step call started from, to return to it after a blow-up.
template <class R>
struct CopyState {
    const Real4<R>* fromPos;
    const Image* fromImage;
    const Real4<R>* fromVel;
    Real4<R>* toPos;
    Image* toImage;
    Real4<R>* toVel;
    const Real4<R>* fromDir = nullptr;  // orientations, copied when both are given
    Real4<R>* toDir = nullptr;
    const Real4<R>* fromMagnetization = nullptr;  // magnetic moments, copied when both are given
    Real4<R>* toMagnetization = nullptr;
    SMD_HD void operator()(int64_t i) const {
        toPos[i] = fromPos[i];
        toImage[i] = fromImage[i];
        toVel[i] = fromVel[i];
        if (fromDir && toDir) toDir[i] = fromDir[i];
        if (fromMagnetization && toMagnetization) toMagnetization[i] = fromMagnetization[i];
    }
};

}  // namespace structmd
