#pragma once
// Counter-based random numbers (Random123 Philox): a draw is a pure function of (seed, stream,
// counter), so the same seed gives the same numbers on any backend, thread count or particle order.
#include <Random123/philox.h>

#include <cmath>
#include <cstdint>

#include "core/hd.hpp"
#include "core/noise_key.hpp"

namespace structmd {

// Four independent standard normal numbers for (seed, stream, counter), e.g. stream = particle id
// and counter = step.
SMD_HD SMD_INLINE void normal4(uint64_t seed, uint64_t stream, uint64_t counter, double out[4]) {
    typedef r123::Philox4x32 Generator;
    const Generator::key_type key = {{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32)}};
    const Generator::ctr_type ctr = {{static_cast<uint32_t>(counter), static_cast<uint32_t>(counter >> 32),
                                      static_cast<uint32_t>(stream), static_cast<uint32_t>(stream >> 32)}};
    const Generator::ctr_type bits = Generator()(ctr, key);
    // Uniforms in (0, 1): never 0, so the logarithm below is finite.
    const double scale = 2.3283064365386963e-10;  // 2^-32
    double u[4];
    for (int k = 0; k < 4; ++k) u[k] = (static_cast<double>(bits.v[k]) + 0.5) * scale;
    const double two_pi = 6.283185307179586;
    for (int k = 0; k < 4; k += 2) {
        const double radius = sqrt(-2.0 * log(u[k]));
        out[k] = radius * cos(two_pi * u[k + 1]);
        out[k + 1] = radius * sin(two_pi * u[k + 1]);
    }
}

}  // namespace structmd
