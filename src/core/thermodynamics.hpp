#pragma once
// The thermodynamic quantities derived from the kinetic energy and the virial, written once for the
// engine (structmd_get_pressure) and the measures (ThermodynamicQuantityMeasure).
#include <cstdint>

namespace structmd {

// P = (2K + W) / (3V): K the kinetic energy, W the trace of the virial sum_i r_i (x) F_i (positive under
// compression), V the box volume.
inline double virial_pressure(double kinetic, double virialTrace, double volume) {
    return (2.0 * kinetic + virialTrace) / (3.0 * volume);
}

// T = 2K / (3 N k_B) for N particles, each with three degrees of freedom; 0 without particles.
inline double kinetic_temperature(double kinetic, int64_t particles, double boltzmann) {
    const double n = static_cast<double>(particles);
    return particles > 0 ? 2.0 * kinetic / (3.0 * n * boltzmann) : 0.0;
}

}  // namespace structmd
