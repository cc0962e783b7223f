#pragma once
// The per-particle quantities of a simulation, read and written through one keyed accessor
// (Simulation::read, write, read_of, write_of) instead of a function each: a quantity's name and its
// values per particle are declared here once, and the API, the views over ranks and the engine all
// go by this table.
#include <cstdint>

namespace structmd {

enum class PerParticle : int32_t {
    positions,           // wrapped into the box
    unwrappedPositions,  // positions + images * box
    images,              // box crossings since the positions were set (integers, as doubles)
    velocities,
    forces,              // of the force field, the host's field and the callbacks: checked finite
    energies,            // each particle's share of the potential energy
    masses,
    types,               // type indices (integers, as doubles)
    radii,
    orientations,        // unit quaternions [q0, q1, q2, q3]; the identity for a simulation without any
    torques,             // lab frame; evaluated with the forces from the first read on
    magneticMoments,     // lab frame; zero for a simulation without magnetization
    pairVirials,         // 1/2 sum_j (-r_ij) (x) F_ij of the non-bonded pair terms, row-major
    externalForces,      // the host's field (write only; a null array clears it and its energy)
};

struct PerParticleTraits {
    const char* name;  // for messages: "the <name> of a subset"
    int width;         // values per particle
};

// What can be read or written of each is the engine's (engine_particles.hpp) and the C API's
// choice; a view over ranks gathers and slices any quantity by its width.
inline const PerParticleTraits& traits(PerParticle q) {
    static constexpr PerParticleTraits kTable[] = {
        {"positions", 3},   {"unwrapped positions", 3}, {"images", 3},          {"velocities", 3},
        {"forces", 3},      {"particle energies", 1},   {"masses", 1},          {"types", 1},
        {"radii", 1},       {"orientations", 4},        {"torques", 3},         {"magnetic moments", 3},
        {"pair virials", 9}, {"external forces", 3},
    };
    return kTable[static_cast<int32_t>(q)];
}

}  // namespace structmd
