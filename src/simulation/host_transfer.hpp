#pragma once
// Particle arrays between the caller's layout (3n doubles in id order) and the engine's (Real4 on
// the backend, type in w of positions, mass in w of velocities). Host code, compiled once per
// precision (host_transfer.cpp), not once per backend.
#include <array>
#include <cstdint>
#include <vector>

#include "core/box.hpp"
#include "core/vec.hpp"
#include "simulation/simulation_spec.hpp"

namespace structmd {

// Writes into positions and images (room for m each) the m particles ids[0..m) (valid, distinct
// ids; null ids: every particle 0..m-1) from their 3m coordinates xyz in the order of ids, wrapped
// into the box; images count the box lengths removed, so the unwrapped positions are the ones
// given. Throws ERR_ARGUMENT naming the particle for a coordinate that is not finite or lies beyond
// 1e8 box lengths; the outputs are then partly written, the caller's state untouched.
template <class R>
void pack_positions_of(const double* xyz, const int64_t* ids, int64_t m, const std::array<double, 3>& box,
                       const std::vector<int32_t>& types, Real4<R>* positions, Image* images);

// The velocities of the m particles ids[0..m) (null ids: every particle), in the order of ids, each
// with its mass.
template <class R>
void pack_velocities_of(const double* v, const int64_t* ids, int64_t m, const std::vector<double>& masses,
                        Real4<R>* velocities);

template <class R>
void unpack_vectors(const Real4<R>* values, int64_t m, double* xyz);

// Maxwell-Boltzmann velocities at spec.velocityKT, keyed by (seed, particle id), with the
// centre-of-mass momentum removed so the system does not drift.
std::vector<double> maxwell_boltzmann(const SimulationSpec& spec);

std::vector<double> flatten(const std::vector<std::array<double, 3>>& vectors);

}  // namespace structmd
