#pragma once
// What keys a particle's noise besides its purpose and the step (core/random.hpp draws it): apart
// from the generator, so that the particles' state (and the engine headers a plugin compiles
// against) does not need Random123.
#include <cstdint>

namespace structmd {

// The system's seed, and the global id of the engine's slot 0 (non-zero when the engine holds a
// share of the batches, parallel/), so that a particle draws the same numbers whichever share of the
// system an engine holds. ids: the global id of every slot, on the backend, where the slots are not
// a run of consecutive ids (a spatial domain's owned particles and ghosts); null otherwise.
struct NoiseKey {
    uint64_t seed = 0;
    int64_t firstId = 0;
    const int64_t* ids = nullptr;
};

}  // namespace structmd
