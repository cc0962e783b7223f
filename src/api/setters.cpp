// Changing the state from the host: positions, velocities, box and external forces. Every value is
// checked before anything changes, so a rejected call leaves the state as it was.
#include <cmath>

#include "api/handle.hpp"

using namespace structmd;
using namespace structmd::api;

namespace {

void require_finite(const double* values, int64_t count, const char* name) {
    for (int64_t k = 0; k < count; ++k)
        if (!std::isfinite(values[k]))
            throw Error(STRUCTMD_ERR_ARGUMENT, std::string(name) + "[" + std::to_string(k) +
                                                   "]: not a finite number (particle id " +
                                                   std::to_string(k / 3) + ")");
}

}  // namespace

extern "C" {

structmd_status structmd_set_positions(structmd_sim* sim, const double* xyz, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_count(loaded(s), n, xyz, "xyz");
        require_finite(xyz, 3 * n, "xyz");
        s.simulation->set_positions(xyz);
    });
}

structmd_status structmd_set_velocities(structmd_sim* sim, const double* v, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_count(loaded(s), n, v, "v");
        require_finite(v, 3 * n, "v");
        s.simulation->set_velocities(v);
    });
}

structmd_status structmd_set_box(structmd_sim* sim, const double lengths[3]) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        require_pointer(lengths, "lengths");
        for (int d = 0; d < 3; ++d)
            if (!(lengths[d] > 0.0) || !std::isfinite(lengths[d]))
                throw Error(STRUCTMD_ERR_ARGUMENT, "lengths[" + std::to_string(d) + "]: expected a positive length");
        simulation.set_box(lengths);
    });
}

structmd_status structmd_set_external_forces(structmd_sim* sim, const double* f, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        if (f == nullptr && n == 0) {
            simulation.set_external_forces(nullptr);
            return;
        }
        require_count(simulation, n, f, "f");
        require_finite(f, 3 * n, "f");
        simulation.set_external_forces(f);
    });
}

}  // extern "C"
