#pragma once
// Gaussian noise and Maxwell-Boltzmann velocities for the stochastic integrators, from the
// counter-based generator keyed by (seed, particle id, step): the same seed gives the same numbers
// on any backend, thread count or particle order.
#include <cmath>
#include <cstdint>

#include "core/random.hpp"
#include "core/vec.hpp"
#include "integrators/integrator.hpp"
#include "state/step_clock.hpp"

namespace structmd {

// What a draw is for: each use has its own stream, so no two uses see the same numbers.
enum class NoisePurpose : uint64_t { initialVelocities = 0, integrator = 1, velocityReset = 2, rotation = 3, magnetization = 4,
                                    hydrodynamics = 5, randomFiniteDifference = 6, pairs = 7 };

// The global id of the particle in `slot`.
SMD_HD SMD_INLINE uint64_t global_id(NoiseKey key, int64_t slot) {
    return static_cast<uint64_t>(key.ids ? key.ids[slot] : slot + key.firstId);
}

// Three independent N(0, 1) numbers for the particle in `slot` at `step`, keyed by its global id.
template <class R>
SMD_HD SMD_INLINE Vec3<R> gaussian3(NoiseKey key, NoisePurpose purpose, int64_t slot, int64_t step) {
    const uint64_t id = global_id(key, slot);
    double xi[4];
    normal4(key.seed, (static_cast<uint64_t>(purpose) << 48) ^ id, static_cast<uint64_t>(step), xi);
    return {R(xi[0]), R(xi[1]), R(xi[2])};
}

// One N(0, 1) number shared by the pair of particles with global ids a and b (below 2^32), the same
// whichever of the two asks, at `step`: a force made of it is equal and opposite on the two. The
// ids fill the stream and the purpose the counter's top 16 bits, so no particle's draw (whose
// counter is the step alone) is ever the same.
template <class R>
SMD_HD SMD_INLINE R pair_gaussian(uint64_t seed, uint64_t a, uint64_t b, int64_t step) {
    const uint64_t low = a < b ? a : b, high = a < b ? b : a;
    double xi[4];
    normal4(seed, (high << 32) | low, (static_cast<uint64_t>(NoisePurpose::pairs) << 48) ^ static_cast<uint64_t>(step), xi);
    return R(xi[0]);
}

// Velocities drawn from Maxwell-Boltzmann at kT (mass in v.w), for the particles of the group.
template <class R>
struct DrawThermalVelocities {
    Real4<R>* vel;
    const uint8_t* group;
    NoiseKey noiseKey;
    ClockView now;
    R kT;
    SMD_HD void operator()(int64_t i) const {
        if ((group && !group[i]) || held_fixed(vel[i])) return;
        Real4<R> v = vel[i];
        const Vec3<R> xi = gaussian3<R>(noiseKey, NoisePurpose::velocityReset, i, now.step());
        const R sigma = sqrt(kT / v.w);
        v.x = sigma * xi.x;
        v.y = sigma * xi.y;
        v.z = sigma * xi.z;
        vel[i] = v;
    }
};

}  // namespace structmd
