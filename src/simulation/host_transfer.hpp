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

// Wraps the positions into the box; images count the box lengths removed, so the unwrapped
// positions are the ones given. Throws ERR_ARGUMENT naming the particle for a coordinate that is
// not finite or lies beyond 1e8 box lengths.
template <class R>
void pack_positions(const double* xyz, const std::array<double, 3>& box, const std::vector<int32_t>& types,
                    std::vector<Real4<R>>& positions, std::vector<Image>& images);

// The same for the m particles ids[0..m) (valid, distinct ids): xyz holds their 3m coordinates in
// the order of ids, and positions and images come out in that order. pack_positions is this with
// every id in order.
template <class R>
void pack_positions_of(const double* xyz, const int64_t* ids, int64_t m, const std::array<double, 3>& box,
                       const std::vector<int32_t>& types, std::vector<Real4<R>>& positions, std::vector<Image>& images);

template <class R>
std::vector<Real4<R>> pack_velocities(const double* v, const std::vector<double>& masses);

// The velocities of the m particles ids[0..m), in the order of ids, each with its mass.
template <class R>
std::vector<Real4<R>> pack_velocities_of(const double* v, const int64_t* ids, int64_t m,
                                         const std::vector<double>& masses);

template <class R>
void unpack_vectors(const std::vector<Real4<R>>& values, double* xyz);

// Maxwell-Boltzmann velocities at spec.velocityKT, keyed by (seed, particle id), with the
// centre-of-mass momentum removed so the system does not drift.
std::vector<double> maxwell_boltzmann(const SimulationSpec& spec);

std::vector<double> flatten(const std::vector<std::array<double, 3>>& vectors);

}  // namespace structmd
