#include "simulation/simulation.hpp"

#include <vector>

namespace structmd {

namespace {

// Integers read as doubles (types, images), handed over as the integers they are.
void read_integers(Simulation& sim, PerParticle q, int32_t* out) {
    std::vector<double> values(static_cast<size_t>(traits(q).width * sim.particle_count()));
    sim.read(q, values.data());
    for (size_t k = 0; k < values.size(); ++k) out[k] = static_cast<int32_t>(values[k]);
}

}  // namespace

void Simulation::get_types(int32_t* types) { read_integers(*this, PerParticle::types, types); }
void Simulation::get_images(int32_t* images) { read_integers(*this, PerParticle::images, images); }

Simulation::Thermodynamics Simulation::thermodynamics() {
    Thermodynamics t;
    const std::array<double, 9> w = virial();
    t.virialTrace = w[0] + w[4] + w[8];
    if (const std::optional<double> kT = overdamped_kT()) {
        t.temperature = *kT / boltzmann();
        t.pressure = (static_cast<double>(particle_count()) * *kT + t.virialTrace / 3.0) / volume();
    } else {
        t.kinetic = energy("kinetic");
        t.temperature = kinetic_temperature(t.kinetic, massive_count(), boltzmann());
        t.pressure = virial_pressure(t.kinetic, t.virialTrace, volume());
    }
    return t;
}

}  // namespace structmd
