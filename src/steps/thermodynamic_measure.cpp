#include "steps/thermodynamic_measure.hpp"

#include <algorithm>


namespace structmd {

ThermodynamicMeasure::ThermodynamicMeasure(std::string name, int64_t interval, int64_t start, int64_t end,
                                           std::string outputPath)
    : SimulationStep(std::move(name), interval, start, end), outputPath_(std::move(outputPath)) {}

void ThermodynamicMeasure::run(Simulation& sim) {
    std::vector<std::string> terms = sim.energy_terms();
    std::sort(terms.begin(), terms.end());
    if (!file_) {
        std::string header = "#step particles volume";
        for (const std::string& term : terms) header += " " + term;
        // The host's field energy comes last, so the columns before it keep their places.
        header += " kinetic potential total temperature virial pressure external";
        file_.emplace("simulationStep." + name(), outputPath_, std::move(header));
    }
    std::FILE* out = file_->stream();
    // A comment line wherever the dynamics turns overdamped or back, so the columns explain themselves.
    const bool overdamped = sim.overdamped_kT().has_value();
    if (overdamped != overdamped_) {
        overdamped_ = overdamped;
        std::fprintf(out, overdamped ? "# from step %lld: overdamped (Brownian) dynamics, no velocities: kinetic is 0, "
                                       "temperature is the bath's, pressure's ideal part uses it\n"
                                     : "# from step %lld: inertial dynamics: kinetic and temperature from the "
                                       "velocities\n",
                     static_cast<long long>(sim.current_step()));
    }
    std::fprintf(out, "%lld %lld %.10g", static_cast<long long>(sim.current_step()),
                 static_cast<long long>(sim.particle_count()), sim.volume());
    double potential = 0.0;
    for (const std::string& term : terms) {
        const double e = sim.energy(term);
        potential += e;
        std::fprintf(out, " %.10g", e);
    }
    const Simulation::Thermodynamics thermo = sim.thermodynamics();
    const double external = sim.energy("external");
    std::fprintf(out, " %.10g %.10g %.10g %.10g %.10g %.10g %.10g\n", thermo.kinetic, potential,
                 thermo.kinetic + potential + external, thermo.temperature, thermo.virialTrace, thermo.pressure,
                 external);
    file_->flush();
}

namespace {

// The measure covers the whole system: a group other than "All" is refused.
std::unique_ptr<SimulationStep> make(const StepInput& in) {
    in.require_all_particles();
    return std::make_unique<ThermodynamicMeasure>(in.name, in.interval(), in.start(), in.end(),
                                                  in.parameters.text("outputFilePath"));
}

}  // namespace

SimulationStepEntry thermodynamic_measure_entry() {
    return {{"ThermodynamicMeasure", "ThermodynamicQuantityMeasure"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr}}),
            make};
}

}  // namespace structmd
