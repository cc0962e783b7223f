#include "steps/thermodynamic_measure.hpp"

#include <algorithm>

#include "core/thermodynamics.hpp"

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
    std::fprintf(out, "%lld %lld %.10g", static_cast<long long>(sim.current_step()),
                 static_cast<long long>(sim.particle_count()), sim.volume());
    double potential = 0.0;
    for (const std::string& term : terms) {
        const double e = sim.energy(term);
        potential += e;
        std::fprintf(out, " %.10g", e);
    }
    const double kinetic = sim.energy("kinetic");
    const double external = sim.external_energy();
    const std::array<double, 9> w = sim.virial();
    const double trace = w[0] + w[4] + w[8];
    std::fprintf(out, " %.10g %.10g %.10g %.10g %.10g %.10g %.10g\n", kinetic, potential, kinetic + potential + external,
                 kinetic_temperature(kinetic, sim.particle_count(), sim.boltzmann()), trace,
                 virial_pressure(kinetic, trace, sim.volume()), external);
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
