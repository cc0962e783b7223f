#include "steps/mean_square_displacement.hpp"

namespace structmd {

MeanSquareDisplacement::MeanSquareDisplacement(std::string name, int64_t interval, int64_t start, int64_t end,
                                               std::string outputPath, std::vector<uint8_t> members)
    : GroupMeasureStep(std::move(name), interval, start, end, std::move(outputPath), "#step time msd",
                       std::move(members)) {}

void MeanSquareDisplacement::run(Simulation& sim) {
    const int64_t n = sim.particle_count();
    std::vector<double> xyz(3 * n);
    sim.get_unwrapped_positions(xyz.data());
    if (reference_.empty()) reference_ = xyz;
    double sum = 0.0;
    int64_t count = 0;
    for (int64_t i = 0; i < n; ++i) {
        if (!measured(i)) continue;
        ++count;
        for (int d = 0; d < 3; ++d) {
            const double delta = xyz[3 * i + d] - reference_[3 * i + d];
            sum += delta * delta;
        }
    }
    const double msd = count > 0 ? sum / static_cast<double>(count) : 0.0;
    write_line(sim, {msd});
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
