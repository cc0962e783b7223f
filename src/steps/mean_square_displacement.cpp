#include "steps/mean_square_displacement.hpp"

namespace structmd {

MeanSquareDisplacement::MeanSquareDisplacement(std::string name, int64_t interval, int64_t start, int64_t end,
                                               std::string outputPath, std::vector<uint8_t> members)
    : SimulationStep(name, interval, start, end),
      file_("simulationStep." + name, std::move(outputPath), "#step time msd"),
      members_(std::move(members)) {}

void MeanSquareDisplacement::run(Simulation& sim) {
    const int64_t n = sim.particle_count();
    std::vector<double> xyz(3 * n);
    sim.get_unwrapped_positions(xyz.data());
    std::FILE* out = file_.stream();
    if (reference_.empty()) reference_ = xyz;
    double sum = 0.0;
    int64_t measured = 0;
    for (int64_t i = 0; i < n; ++i) {
        if (!members_.empty() && !members_[i]) continue;
        ++measured;
        for (int d = 0; d < 3; ++d) {
            const double delta = xyz[3 * i + d] - reference_[3 * i + d];
            sum += delta * delta;
        }
    }
    const double msd = measured > 0 ? sum / static_cast<double>(measured) : 0.0;
    std::fprintf(out, "%lld %.17g %.17g\n", static_cast<long long>(sim.current_step()), sim.current_time(), msd);
    file_.flush();
}

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    return std::make_unique<MeanSquareDisplacement>(in.name, in.interval(), in.start(), in.end(),
                                                    in.parameters.text("outputFilePath"), in.members);
}

}  // namespace

SimulationStepEntry mean_square_displacement_entry() {
    return {{"GeometricalMeasure", "MeanSquareDisplacement"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr}}),
            make};
}

}  // namespace structmd
