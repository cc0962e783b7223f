// Reading and changing a subset of the particles by id: values are m x 3 in the order of the ids,
// and only those m entries (and the ids) move between the host and the backend. Every argument is
// checked before anything is written or changed, so a rejected call leaves the state as it was.
#include <algorithm>
#include <cmath>
#include <vector>

#include "api/handle.hpp"

using namespace structmd;
using namespace structmd::api;

namespace {

// m >= 0; with m > 0, both pointers given and every id a particle's, none twice. Returns false for
// m == 0 (nothing to do). O(m) per call, whatever the number of particles: a coupling loop calls
// this every step.
bool require_subset(structmd_sim& s, const int64_t* ids, int64_t m, const void* values, const char* valuesName) {
    const Simulation& simulation = loaded(s);
    if (m < 0) throw Error(STRUCTMD_ERR_ARGUMENT, "m: expected a count >= 0, got " + std::to_string(m));
    if (m == 0) return false;
    require_pointer(ids, "ids");
    require_pointer(values, valuesName);
    const int64_t n = simulation.particle_count();
    for (int64_t k = 0; k < m; ++k)
        if (ids[k] < 0 || ids[k] >= n)
            throw Error(STRUCTMD_ERR_ARGUMENT, "ids[" + std::to_string(k) + "]: particle id " + std::to_string(ids[k]) +
                                                   " does not exist (ids are 0.." + std::to_string(n - 1) + ")");
    if (s.distinctIds.size() == static_cast<size_t>(m) && std::equal(ids, ids + m, s.distinctIds.begin())) return true;
    if (static_cast<int64_t>(s.idSeenAt.size()) != n) s.idSeenAt.assign(static_cast<size_t>(n), 0);
    const uint64_t call = ++s.subsetCalls;
    for (int64_t k = 0; k < m; ++k) {
        uint64_t& seen = s.idSeenAt[static_cast<size_t>(ids[k])];
        if (seen == call) {
            const int64_t first = std::find(ids, ids + k, ids[k]) - ids;
            throw Error(STRUCTMD_ERR_ARGUMENT, "ids: particle id " + std::to_string(ids[k]) + " is given twice (ids[" +
                                                   std::to_string(first) + "] and ids[" + std::to_string(k) +
                                                   "]); each id may appear once");
        }
        seen = call;
    }
    s.distinctIds.assign(ids, ids + m);
    return true;
}

void require_finite(const double* values, const int64_t* ids, int64_t m, const char* name) {
    for (int64_t k = 0; k < 3 * m; ++k)
        if (!std::isfinite(values[k]))
            throw Error(STRUCTMD_ERR_ARGUMENT, std::string(name) + "[" + std::to_string(k) +
                                                   "]: not a finite number (particle id " +
                                                   std::to_string(ids[k / 3]) + ")");
}

}  // namespace

extern "C" {

structmd_status structmd_get_positions_of(structmd_sim* sim, const int64_t* ids, int64_t m, double* xyz) {
    return with_handle(sim, [&](structmd_sim& s) {
        if (require_subset(s, ids, m, xyz, "xyz")) s.simulation->read_of(PerParticle::positions, ids, m, xyz);
    });
}

structmd_status structmd_get_velocities_of(structmd_sim* sim, const int64_t* ids, int64_t m, double* v) {
    return with_handle(sim, [&](structmd_sim& s) {
        if (require_subset(s, ids, m, v, "v")) s.simulation->read_of(PerParticle::velocities, ids, m, v);
    });
}

structmd_status structmd_get_forces_of(structmd_sim* sim, const int64_t* ids, int64_t m, double* f) {
    return with_handle(sim, [&](structmd_sim& s) {
        if (require_subset(s, ids, m, f, "f")) s.simulation->read_of(PerParticle::forces, ids, m, f);
    });
}

structmd_status structmd_set_positions_of(structmd_sim* sim, const int64_t* ids, int64_t m, const double* xyz) {
    return with_handle(sim, [&](structmd_sim& s) {
        if (!require_subset(s, ids, m, xyz, "xyz")) return;
        require_finite(xyz, ids, m, "xyz");
        s.simulation->write_of(PerParticle::positions, ids, m, xyz);
    });
}

structmd_status structmd_set_velocities_of(structmd_sim* sim, const int64_t* ids, int64_t m, const double* v) {
    return with_handle(sim, [&](structmd_sim& s) {
        if (!require_subset(s, ids, m, v, "v")) return;
        require_finite(v, ids, m, "v");
        s.simulation->write_of(PerParticle::velocities, ids, m, v);
    });
}

structmd_status structmd_set_external_forces_of(structmd_sim* sim, const int64_t* ids, int64_t m, const double* f) {
    return with_handle(sim, [&](structmd_sim& s) {
        if (!require_subset(s, ids, m, f, "f")) return;
        require_finite(f, ids, m, "f");
        s.simulation->write_of(PerParticle::externalForces, ids, m, f);
    });
}

}  // extern "C"
