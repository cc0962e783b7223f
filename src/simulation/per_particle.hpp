#pragma once
// The per-particle quantities of a simulation, read and written through one keyed accessor
// (Simulation::read, write, read_of, write_of) instead of a function each: a quantity's name, its
// values per particle and what may be done with it are declared here once, and the API, the views
// over ranks and the engine all go by this table.
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
    bool readable;
    bool writable;      // as a whole array
    bool subsetReadable;  // by id (read_of)
    bool subsetWritable;  // by id (write_of)
};

inline const PerParticleTraits& traits(PerParticle q) {
    static constexpr PerParticleTraits kTable[] = {
        {"positions", 3, true, true, true, true},
        {"unwrapped positions", 3, true, false, false, false},
        {"images", 3, true, false, false, false},
        {"velocities", 3, true, true, true, true},
        {"forces", 3, true, false, true, false},
        {"particle energies", 1, true, false, false, false},
        {"masses", 1, true, false, false, false},
        {"types", 1, true, false, false, false},
        {"radii", 1, true, false, false, false},
        {"orientations", 4, true, true, false, false},
        {"torques", 3, true, false, false, false},
        {"magnetic moments", 3, true, false, false, false},
        {"pair virials", 9, true, false, false, false},
        {"external forces", 3, false, true, false, true},
    };
    return kTable[static_cast<int32_t>(q)];
}

}  // namespace structmd
