#include "steps/thermodynamic_measure.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "core/error.hpp"

namespace structmd {

ThermodynamicMeasure::ThermodynamicMeasure(std::string name, int64_t interval, int64_t start, int64_t end,
                                           std::string outputPath)
    : SimulationStep(std::move(name), interval, start, end),
      outputPath_(std::move(outputPath)),
      file_(nullptr, &std::fclose) {}

void ThermodynamicMeasure::run(Simulation& sim) {
    std::vector<std::string> terms = sim.energy_terms();
    std::sort(terms.begin(), terms.end());
    // Opened at the first firing, not at load, so a load that fails later leaves an old file alone.
    if (!file_) {
        file_.reset(std::fopen(outputPath_.c_str(), "w"));
        if (!file_)
            throw Error(STRUCTMD_ERR_IO, "simulationStep." + name() + ": cannot open '" + outputPath_ +
                                             "' for writing: " + std::strerror(errno));
        std::fprintf(file_.get(), "#step particles volume");
        for (const std::string& term : terms) std::fprintf(file_.get(), " %s", term.c_str());
        std::fprintf(file_.get(), " kinetic potential total temperature virial pressure\n");
    }
    std::fprintf(file_.get(), "%lld %lld %.10g", static_cast<long long>(sim.current_step()),
                 static_cast<long long>(sim.particle_count()), sim.volume());
    double potential = 0.0;
    for (const std::string& term : terms) {
        const double e = sim.energy(term);
        potential += e;
        std::fprintf(file_.get(), " %.10g", e);
    }
    const double kinetic = sim.energy("kinetic");
    const std::array<double, 9> w = sim.virial();
    const double trace = w[0] + w[4] + w[8];
    const double n = static_cast<double>(sim.particle_count());
    const double temperature = n > 0 ? 2.0 * kinetic / (3.0 * n * sim.boltzmann()) : 0.0;
    const double pressure = (2.0 * kinetic + trace) / (3.0 * sim.volume());
    std::fprintf(file_.get(), " %.10g %.10g %.10g %.10g %.10g %.10g\n", kinetic, potential, kinetic + potential,
                 temperature, trace, pressure);
    if (std::fflush(file_.get()) != 0)
        throw Error(STRUCTMD_ERR_IO, "simulationStep." + name() + ": cannot write '" + outputPath_ +
                                         "': " + std::strerror(errno));
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
