// Reading the state: per-particle arrays in id order, energies, virial, box, step and time.
#include <cmath>
#include <string>
#include <vector>

#include "api/handle.hpp"

using namespace structmd;
using namespace structmd::api;

namespace {

// A getter hands over finite numbers only: a NaN or inf (two particles on top of each other, a term
// evaluated outside its domain) is STRUCTMD_ERR_NUMERICAL naming what and where, and the caller's
// array is left as it was.
void require_finite(const Simulation& simulation, const double* values, size_t count, const std::string& what,
                    int width = 0) {
    for (size_t k = 0; k < count; ++k) {
        if (std::isfinite(values[k])) continue;
        const std::string which = width > 0 ? " of particle id " + std::to_string(k / static_cast<size_t>(width)) : "";
        throw Error(STRUCTMD_ERR_NUMERICAL, "step " + std::to_string(simulation.current_step()) + ": the " + what +
                                                which + " is not finite (" + std::to_string(values[k]) +
                                                "): overlapping particles, or a term outside its domain?");
    }
}

}  // namespace

extern "C" {

structmd_status structmd_get_num_particles(const structmd_sim* sim, int64_t* n) {
    return with_handle(sim, [&](const structmd_sim& s) {
        require_pointer(n, "n");
        *n = loaded(s).particle_count();
    });
}

structmd_status structmd_get_ids(structmd_sim* sim, int64_t* ids, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_count(loaded(s), n, ids, "ids");
        for (int64_t i = 0; i < n; ++i) ids[i] = i;
    });
}

structmd_status structmd_get_positions(structmd_sim* sim, double* xyz, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_count(loaded(s), n, xyz, "xyz");
        s.simulation->read(PerParticle::positions, xyz);
    });
}

structmd_status structmd_get_velocities(structmd_sim* sim, double* v, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_count(loaded(s), n, v, "v");
        s.simulation->read(PerParticle::velocities, v);
    });
}

structmd_status structmd_get_orientations(structmd_sim* sim, double* q, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_count(loaded(s), n, q, "q");
        s.simulation->read(PerParticle::orientations, q);
    });
}

structmd_status structmd_get_magnetic_moments(structmd_sim* sim, double* m, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_count(loaded(s), n, m, "m");
        s.simulation->read(PerParticle::magneticMoments, m);
    });
}

structmd_status structmd_get_torques(structmd_sim* sim, double* t, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_count(loaded(s), n, t, "t");
        s.simulation->read(PerParticle::torques, t);
    });
}

structmd_status structmd_get_forces(structmd_sim* sim, double* f, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_count(loaded(s), n, f, "f");
        s.simulation->read(PerParticle::forces, f);
    });
}

structmd_status structmd_get_particle_energies(structmd_sim* sim, double* e, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_count(loaded(s), n, e, "e");
        std::vector<double> energies(static_cast<size_t>(n));
        s.simulation->read(PerParticle::energies, energies.data());
        require_finite(*s.simulation, energies.data(), energies.size(), "energy", 1);
        std::copy(energies.begin(), energies.end(), e);
    });
}

structmd_status structmd_get_masses(structmd_sim* sim, double* m, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_count(loaded(s), n, m, "m");
        s.simulation->read(PerParticle::masses, m);
    });
}

structmd_status structmd_get_types(structmd_sim* sim, int32_t* type_index, int64_t n) {
    return with_handle(sim, [&](structmd_sim& s) {
        require_count(loaded(s), n, type_index, "type_index");
        s.simulation->get_types(type_index);
    });
}

structmd_status structmd_get_energy(structmd_sim* sim, const char* term, double* value) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        require_pointer(term, "term");
        require_pointer(value, "value");
        const double energy = simulation.energy(term);
        require_finite(simulation, &energy, 1, std::string("\"") + term + "\" energy");
        *value = energy;
    });
}

structmd_status structmd_get_virial(structmd_sim* sim, double w[9]) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        require_pointer(w, "w");
        const std::array<double, 9> virial = simulation.virial();
        require_finite(simulation, virial.data(), virial.size(), "virial");
        std::copy(virial.begin(), virial.end(), w);
    });
}

structmd_status structmd_get_pressure(structmd_sim* sim, double* p) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        require_pointer(p, "p");
        const double pressure = simulation.pressure();
        require_finite(simulation, &pressure, 1, "pressure");
        *p = pressure;
    });
}

structmd_status structmd_get_temperature(structmd_sim* sim, double* t) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        require_pointer(t, "t");
        const double temperature = simulation.thermodynamics().temperature;
        require_finite(simulation, &temperature, 1, "temperature");
        *t = temperature;
    });
}

structmd_status structmd_get_box(structmd_sim* sim, double lengths[3]) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        require_pointer(lengths, "lengths");
        const std::array<double, 3> box = simulation.box();
        std::copy(box.begin(), box.end(), lengths);
    });
}

structmd_status structmd_get_step(const structmd_sim* sim, int64_t* step) {
    return with_handle(sim, [&](const structmd_sim& s) {
        require_pointer(step, "step");
        *step = loaded(s).current_step();
    });
}

structmd_status structmd_get_time(const structmd_sim* sim, double* t) {
    return with_handle(sim, [&](const structmd_sim& s) {
        require_pointer(t, "t");
        *t = loaded(s).current_time();
    });
}

}  // extern "C"
