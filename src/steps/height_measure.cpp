#include "steps/height_measure.hpp"

#include <algorithm>
#include <functional>

#include "core/error.hpp"

namespace structmd {

HeightMeasure::HeightMeasure(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                             std::vector<int64_t> members, int64_t averaged)
    : SimulationStep(name, interval, start, end),
      file_("simulationStep." + name, std::move(outputPath), "#step time height"),
      members_(std::move(members)),
      averaged_(averaged) {}

void HeightMeasure::run(Simulation& sim) {
    std::vector<double> xyz(3 * sim.particle_count());
    sim.get_unwrapped_positions(xyz.data());
    std::vector<double> heights;
    heights.reserve(members_.size());
    for (int64_t id : members_) heights.push_back(xyz[3 * id + 2]);
    std::partial_sort(heights.begin(), heights.begin() + averaged_, heights.end(), std::greater<double>());
    double sum = 0.0;
    for (int64_t k = 0; k < averaged_; ++k) sum += heights[k];
    std::fprintf(file_.stream(), "%lld %.17g %.17g\n", static_cast<long long>(sim.current_step()), sim.current_time(),
                 sum / static_cast<double>(averaged_));
    file_.flush();
}

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    std::vector<int64_t> members = in.member_ids();
    const int64_t averaged = in.parameters.integer("particleNumberAverage");
    if (averaged > static_cast<int64_t>(members.size()))
        throw input_error(in.parameters.path("particleNumberAverage"),
                          "expected at most the " + std::to_string(members.size()) +
                              " particles measured, got " + std::to_string(averaged));
    return std::make_unique<HeightMeasure>(in.name, in.interval(), in.start(), in.end(),
                                           in.parameters.text("outputFilePath"), std::move(members), averaged);
}

}  // namespace

SimulationStepEntry height_measure_entry() {
    return {{"GeometricalMeasure", "Height"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr},
                             {"particleNumberAverage", StepValue::integer, int64_t{1}, Must::be_positive, "",
                              "at most the number of particles measured"}}),
            make};
}

}  // namespace structmd
