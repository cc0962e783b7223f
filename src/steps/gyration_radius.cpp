#include "steps/gyration_radius.hpp"

#include <cmath>

namespace structmd {

GyrationRadius::GyrationRadius(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                               std::vector<uint8_t> members)
    : GroupMeasureStep(std::move(name), interval, start, end, std::move(outputPath), "#step time Rg",
                       std::move(members)) {}

void GyrationRadius::run(Simulation& sim) {
    const int64_t n = sim.particle_count();
    std::vector<double> xyz(3 * n);
    sim.get_unwrapped_positions(xyz.data());
    // Two passes (mean, then spread about it) rather than <r^2> - <r>^2, which cancels badly once
    // the particles have drifted far from the origin.
    double mean[3] = {0.0, 0.0, 0.0};
    int64_t count = 0;
    for (int64_t i = 0; i < n; ++i)
        if (measured(i)) {
            ++count;
            for (int d = 0; d < 3; ++d) mean[d] += xyz[3 * i + d];
        }
    double rg = 0.0;
    if (count > 0) {
        for (double& m : mean) m /= static_cast<double>(count);
        double spread = 0.0;
        for (int64_t i = 0; i < n; ++i)
            if (measured(i))
                for (int d = 0; d < 3; ++d) {
                    const double delta = xyz[3 * i + d] - mean[d];
                    spread += delta * delta;
                }
        rg = std::sqrt(spread / static_cast<double>(count));
    }
    write_line(sim, {rg});
}

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    return std::make_unique<GyrationRadius>(in.name, in.interval(), in.start(), in.end(),
                                            in.parameters.text("outputFilePath"), in.members);
}

}  // namespace

SimulationStepEntry gyration_radius_entry() {
    return {{"GeometricalMeasure", "GyrationRadius"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr}}),
            make};
}

}  // namespace structmd
