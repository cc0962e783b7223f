#include "steps/potential_measure.hpp"

#include <array>
#include <cmath>

#include "steps/particle_list_measure.hpp"

namespace structmd {

PotentialMeasure::PotentialMeasure(std::string name, int64_t interval, int64_t start, int64_t end,
                                   std::string outputPath, std::vector<int64_t> ids)
    : SimulationStep(name, interval, start, end), outputPath_(std::move(outputPath)), ids_(std::move(ids)) {}

void PotentialMeasure::run(Simulation& sim) {
    const std::vector<std::string> terms = sim.energy_terms();
    if (!file_) {
        std::string header = "# id";
        for (const std::string& term : terms)
            for (const char* column : {"Energy", "ForceX", "ForceY", "ForceZ", "ForceMod", "TorqueX", "TorqueY",
                                       "TorqueZ", "TorqueMod"})
                header += " " + term + column;
        file_.emplace("simulationStep." + name(), outputPath_, std::move(header));
    }
    const int64_t n = sim.particle_count();
    std::vector<std::vector<double>> energies(terms.size(), std::vector<double>(n));
    std::vector<std::vector<double>> forces(terms.size(), std::vector<double>(3 * n));
    std::vector<std::vector<double>> torques(terms.size(), std::vector<double>(3 * n));
    for (size_t t = 0; t < terms.size(); ++t)
        sim.probes().term_energies_and_forces(terms[t], energies[t].data(), forces[t].data(), torques[t].data());
    std::FILE* out = file_->stream();
    std::fprintf(out, "# %lld\n", static_cast<long long>(sim.current_step()));
    for (int64_t id : ids_) {
        std::fprintf(out, "%lld", static_cast<long long>(id));
        for (size_t t = 0; t < terms.size(); ++t) {
            const double* f = &forces[t][3 * id];
            const double* tau = &torques[t][3 * id];
            std::fprintf(out, " %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g", energies[t][id], f[0], f[1],
                         f[2], std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]), tau[0], tau[1], tau[2],
                         std::sqrt(tau[0] * tau[0] + tau[1] * tau[1] + tau[2] * tau[2]));
        }
        std::fprintf(out, "\n");
    }
    file_->flush();
}

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    std::vector<int64_t> ids;
    for (const std::array<int64_t, 4>& row : read_particle_ids(in, {"id"})) ids.push_back(row[0]);
    return std::make_unique<PotentialMeasure>(in.name, in.interval(), in.start(), in.end(),
                                              in.parameters.text("outputFilePath"), std::move(ids));
}

}  // namespace

SimulationStepEntry potential_measure_entry() {
    return {{"ParticlesListMeasure", "PotentialMeasure"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr}}),
            make,
            {"id"}};
}

}  // namespace structmd
