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
// m == 0 (nothing to do).
bool require_subset(const Simulation& simulation, const int64_t* ids, int64_t m, const void* values,
                    const char* valuesName) {
    if (m < 0) throw Error(STRUCTMD_ERR_ARGUMENT, "m: expected a count >= 0, got " + std::to_string(m));
    if (m == 0) return false;
    require_pointer(ids, "ids");
    require_pointer(values, valuesName);
    const int64_t n = simulation.particle_count();
    for (int64_t k = 0; k < m; ++k)
        if (ids[k] < 0 || ids[k] >= n)
            throw Error(STRUCTMD_ERR_ARGUMENT, "ids[" + std::to_string(k) + "]: particle id " + std::to_string(ids[k]) +
                                                   " does not exist (ids are 0.." + std::to_string(n - 1) + ")");
    // Sorting a copy costs O(m log m) on the host, whatever the number of particles.
    std::vector<int64_t> sorted(ids, ids + m);
    std::sort(sorted.begin(), sorted.end());
    const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
    if (twice != sorted.end()) {
        std::vector<int64_t> where;
        for (int64_t k = 0; k < m && where.size() < 2; ++k)
            if (ids[k] == *twice) where.push_back(k);
        throw Error(STRUCTMD_ERR_ARGUMENT, "ids: particle id " + std::to_string(*twice) + " is given twice (ids[" +
                                               std::to_string(where[0]) + "] and ids[" + std::to_string(where[1]) +
                                               "]); each id may appear once");
    }
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
        if (require_subset(loaded(s), ids, m, xyz, "xyz")) s.simulation->get_positions_of(ids, m, xyz);
    });
}

structmd_status structmd_get_velocities_of(structmd_sim* sim, const int64_t* ids, int64_t m, double* v) {
    return with_handle(sim, [&](structmd_sim& s) {
        if (require_subset(loaded(s), ids, m, v, "v")) s.simulation->get_velocities_of(ids, m, v);
    });
}

structmd_status structmd_get_forces_of(structmd_sim* sim, const int64_t* ids, int64_t m, double* f) {
    return with_handle(sim, [&](structmd_sim& s) {
        if (require_subset(loaded(s), ids, m, f, "f")) s.simulation->get_forces_of(ids, m, f);
    });
}

structmd_status structmd_set_positions_of(structmd_sim* sim, const int64_t* ids, int64_t m, const double* xyz) {
    return with_handle(sim, [&](structmd_sim& s) {
        if (!require_subset(loaded(s), ids, m, xyz, "xyz")) return;
        require_finite(xyz, ids, m, "xyz");
        s.simulation->set_positions_of(ids, m, xyz);
    });
}

structmd_status structmd_set_velocities_of(structmd_sim* sim, const int64_t* ids, int64_t m, const double* v) {
    return with_handle(sim, [&](structmd_sim& s) {
        if (!require_subset(loaded(s), ids, m, v, "v")) return;
        require_finite(v, ids, m, "v");
        s.simulation->set_velocities_of(ids, m, v);
    });
}

structmd_status structmd_set_external_forces_of(structmd_sim* sim, const int64_t* ids, int64_t m, const double* f) {
    return with_handle(sim, [&](structmd_sim& s) {
        if (!require_subset(loaded(s), ids, m, f, "f")) return;
        require_finite(f, ids, m, "f");
        s.simulation->set_external_forces_of(ids, m, f);
    });
}

}  // extern "C"
