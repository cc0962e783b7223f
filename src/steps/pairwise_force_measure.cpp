#include "steps/pairwise_force_measure.hpp"

#include "core/error.hpp"

namespace structmd {

PairwiseForceMeasure::PairwiseForceMeasure(std::string name, int64_t interval, int64_t start, int64_t end,
                                           std::string outputPath, Mode mode, std::vector<int64_t> members)
    : SimulationStep(name, interval, start, end),
      file_("simulationStep." + name, std::move(outputPath),
            mode == Mode::pairwise ? "#From To Fx Fy Fz" : "#Id Fx Fy Fz"),
      mode_(mode),
      members_(std::move(members)) {}

void PairwiseForceMeasure::run(Simulation& sim) {
    std::vector<double> f(3 * sim.particle_count());
    std::FILE* out = file_.stream();
    std::fprintf(out, "# step %lld time %.17g\n", static_cast<long long>(sim.current_step()), sim.current_time());
    if (mode_ == Mode::total) {
        const double still[3] = {0.0, 0.0, 0.0};
        sim.probes().forces_with_displaced(0, still, f.data());
        for (int64_t i : members_)
            std::fprintf(out, "%lld %.17g %.17g %.17g\n", static_cast<long long>(i), f[3 * i], f[3 * i + 1],
                         f[3 * i + 2]);
    } else {
        for (int64_t i : members_) {
            sim.probes().pair_forces_on(i, f.data());
            for (int64_t j : members_) {
                const double* fj = &f[3 * j];
                if (j == i || (fj[0] == 0.0 && fj[1] == 0.0 && fj[2] == 0.0)) continue;
                std::fprintf(out, "%lld %lld %.17g %.17g %.17g\n", static_cast<long long>(j), static_cast<long long>(i),
                             fj[0], fj[1], fj[2]);
            }
        }
    }
    file_.flush();
}

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    const std::string mode = in.parameters.text("mode");
    if (mode != "Pairwise_force" && mode != "Total_force")
        throw input_error(in.parameters.path("mode"),
                          "expected \"Pairwise_force\" or \"Total_force\", got \"" + mode + "\"");
    return std::make_unique<PairwiseForceMeasure>(
        in.name, in.interval(), in.start(), in.end(), in.parameters.text("outputFilePath"),
        mode == "Pairwise_force" ? PairwiseForceMeasure::Mode::pairwise : PairwiseForceMeasure::Mode::total,
        in.member_ids());
}

}  // namespace

SimulationStepEntry pairwise_force_measure_entry() {
    return {{"MechanicalMeasure", "PairwiseForceMeasure"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr},
                             {"mode", StepValue::text, "Pairwise_force", Must::be_finite, "",
                              "\"Pairwise_force\" (the force each particle exerts on each other) or \"Total_force\" "
                              "(each particle's whole force)"}}),
            make};
}

}  // namespace structmd
