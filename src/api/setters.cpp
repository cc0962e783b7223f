// Changing the state from the host: positions, velocities, box and external forces. Every value is
// checked before anything changes, so a rejected call leaves the state as it was.
#include <cmath>

#include "api/handle.hpp"

using namespace structmd;
using namespace structmd::api;

namespace {

// components: values per particle (3 for vectors, 4 for quaternions).
void require_finite(const double* values, int64_t count, const char* name, int components = 3) {
    for (int64_t k = 0; k < count; ++k)
        if (!std::isfinite(values[k]))
            throw Error(STRUCTMD_ERR_ARGUMENT, std::string(name) + "[" + std::to_string(k) +
                                                   "]: not a finite number (particle id " +
                                                   std::to_string(k / components) + ")");
}

// A host normalises in double precision: a norm off by more than rounding is a wrong quaternion.
constexpr double kQuaternionNormTolerance = 1e-6;

void require_unit_quaternions(const double* q, int64_t n) {
    require_finite(q, 4 * n, "q", 4);
    for (int64_t i = 0; i < n; ++i) {
        const double* row = q + 4 * i;
        const double norm2 = row[0] * row[0] + row[1] * row[1] + row[2] * row[2] + row[3] * row[3];
        if (!(std::abs(norm2 - 1.0) <= kQuaternionNormTolerance))
            throw Error(STRUCTMD_ERR_ARGUMENT, "q[" + std::to_string(4 * i) + ".." + std::to_string(4 * i + 3) +
                                                   "]: the orientation of particle id " + std::to_string(i) +
                                                   " is not a unit quaternion (norm^2 = " + std::to_string(norm2) + ")");
    }
}

}  // namespace

extern "C" {

structmd_status structmd_set_positions(structmd_sim* sim, const double* xyz, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_count(loaded(s), n, xyz, "xyz");
        require_finite(xyz, 3 * n, "xyz");
        s.simulation->write(PerParticle::positions, xyz);
    });
}

structmd_status structmd_set_velocities(structmd_sim* sim, const double* v, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_count(loaded(s), n, v, "v");
        require_finite(v, 3 * n, "v");
        s.simulation->write(PerParticle::velocities, v);
    });
}

structmd_status structmd_set_orientations(structmd_sim* sim, const double* q, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_count(loaded(s), n, q, "q");
        require_unit_quaternions(q, n);
        s.simulation->write(PerParticle::orientations, q);
    });
}

structmd_status structmd_set_box(structmd_sim* sim, const double lengths[3]) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        require_pointer(lengths, "lengths");
        // The engine checks each length (0 or infinity: an open axis) against the force field.
        simulation.set_box(lengths);
    });
}

structmd_status structmd_set_external_forces(structmd_sim* sim, const double* f, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        if (f == nullptr && n == 0) {
            simulation.write(PerParticle::externalForces, nullptr);
            return;
        }
        require_count(simulation, n, f, "f");
        require_finite(f, 3 * n, "f");
        simulation.write(PerParticle::externalForces, f);
    });
}

}  // extern "C"
