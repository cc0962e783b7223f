#include "steps/mean_angular_correlation.hpp"

#include "core/quaternion.hpp"

namespace structmd {

MeanAngularCorrelation::MeanAngularCorrelation(std::string name, int64_t interval, int64_t start, int64_t end,
                                               std::string outputPath, std::vector<uint8_t> members)
    : GroupMeasureStep(std::move(name), interval, start, end, std::move(outputPath), "#step time MAC",
                       std::move(members)) {}

void MeanAngularCorrelation::run(Simulation& sim) {
    const int64_t n = sim.particle_count();
    std::vector<double> q(4 * n);
    sim.get_orientations(q.data());
    std::vector<double> axes(3 * n);
    for (int64_t i = 0; i < n; ++i) {
        const Vec3<double> z = body_z(Real4<double>{q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3]});
        axes[3 * i] = z.x;
        axes[3 * i + 1] = z.y;
        axes[3 * i + 2] = z.z;
    }
    if (referenceAxes_.empty()) referenceAxes_ = axes;
    double sum = 0.0;
    int64_t count = 0;
    for (int64_t i = 0; i < n; ++i) {
        if (!measured(i)) continue;
        ++count;
        double cosine = 0.0;
        for (int d = 0; d < 3; ++d) cosine += axes[3 * i + d] * referenceAxes_[3 * i + d];
        sum += cosine;
    }
    write_line(sim, {count > 0 ? sum / static_cast<double>(count) : 0.0});
}

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    return std::make_unique<MeanAngularCorrelation>(in.name, in.interval(), in.start(), in.end(),
                                                    in.parameters.text("outputFilePath"), in.members);
}

}  // namespace

SimulationStepEntry mean_angular_correlation_entry() {
    return {{"GeometricalMeasure", "MeanAngularCorrelation"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr}}),
            make};
}

}  // namespace structmd
