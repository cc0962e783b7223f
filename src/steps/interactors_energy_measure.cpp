#include "steps/interactors_energy_measure.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace structmd {

namespace {

std::string header(const std::vector<std::string>& terms) {
    std::string text = "#step time";
    for (const std::string& term : terms) text += " " + term;
    return text;
}

}  // namespace

InteractorsEnergyMeasure::InteractorsEnergyMeasure(std::string name, int64_t interval, int64_t start, int64_t end,
                                                   std::string outputPath, std::vector<std::string> terms)
    : SimulationStep(name, interval, start, end),
      file_("simulationStep." + name, std::move(outputPath), header(terms)),
      terms_(std::move(terms)) {}

void InteractorsEnergyMeasure::run(Simulation& sim) {
    std::FILE* out = file_.stream();
    std::fprintf(out, "%lld %.17g", static_cast<long long>(sim.current_step()), sim.current_time());
    for (const std::string& term : terms_) std::fprintf(out, " %.17g", sim.energy(term));
    std::fprintf(out, "\n");
    file_.flush();
}

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    in.require_all_particles();  // an entry's energy is the whole system's
    const std::vector<std::string>& entries = in.forceField.entryNames;
    std::vector<std::string> terms = in.parameters.texts("interactorsList");
    for (const std::string& term : terms)
        if (std::find(entries.begin(), entries.end(), term) == entries.end()) {
            std::string known;
            for (const std::string& entry : entries) known += (known.empty() ? "" : ", ") + entry;
            throw input_error(in.parameters.path("interactorsList"),
                              "no interaction entry named '" + term + "' (entries: " + (known.empty() ? "none" : known) +
                                  ")");
        }
    if (terms.empty()) terms = entries;
    return std::make_unique<InteractorsEnergyMeasure>(in.name, in.interval(), in.start(), in.end(),
                                                      in.parameters.text("outputFilePath"), std::move(terms));
}

}  // namespace

SimulationStepEntry interactors_energy_measure_entry() {
    return {{"ThermodynamicMeasure", "InteractorsListEnergyMeasure"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr},
                             {"interactorsList", StepValue::texts, nlohmann::json::array(), Must::be_finite, "",
                              "names of force-field interaction entries; empty: every one"}}),
            make};
}

}  // namespace structmd
