#include "steps/magnetization_measure.hpp"

#include <array>
#include <cmath>

#include "core/error.hpp"

namespace structmd {

MagnetizationMeasure::MagnetizationMeasure(bool mean, std::string name, int64_t interval, int64_t start, int64_t end,
                                           std::string outputPath, std::vector<uint8_t> members)
    : GroupMeasureStep(std::move(name), interval, start, end, std::move(outputPath), "#step time Mx My Mz",
                       std::move(members)),
      mean_(mean) {}

void MagnetizationMeasure::run(Simulation& sim) {
    const int64_t n = sim.particle_count();
    std::vector<double> moments(3 * n);
    sim.get_magnetic_moments(moments.data());
    std::array<double, 3> total{0.0, 0.0, 0.0};
    double magnitudes = 0.0;
    for (int64_t i = 0; i < n; ++i) {
        if (!measured(i)) continue;
        const double* mu = moments.data() + 3 * i;
        for (int d = 0; d < 3; ++d) total[d] += mu[d];
        magnitudes += std::sqrt(mu[0] * mu[0] + mu[1] * mu[1] + mu[2] * mu[2]);
    }
    // Moments all of magnitude 0 have no mean direction: the mean reads 0.
    if (mean_)
        for (double& m : total) m = magnitudes > 0.0 ? m / magnitudes : 0.0;
    write_line(sim, {total[0], total[1], total[2]});
}

namespace {

template <bool Mean>
std::unique_ptr<SimulationStep> make(const StepInput& in) {
    if (in.system.magnetizations.empty())
        throw input_error(in.path + ".type", "a magnetization measure needs the state's 'magnetization' column");
    return std::make_unique<MagnetizationMeasure>(Mean, in.name, in.interval(), in.start(), in.end(),
                                                  in.parameters.text("outputFilePath"), in.members);
}

}  // namespace

SimulationStepEntry total_magnetization_entry() {
    return {{"MagneticMeasure", "MeasureTotalMagnetization"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr}}),
            make<false>};
}

SimulationStepEntry mean_magnetization_entry() {
    return {{"MagneticMeasure", "MeasureMeanMagnetization"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr}}),
            make<true>};
}

}  // namespace structmd
