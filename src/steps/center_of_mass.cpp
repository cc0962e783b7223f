#include "steps/center_of_mass.hpp"

#include <cmath>

namespace structmd {

CenterOfMassMeasure::CenterOfMassMeasure(Quantity quantity, std::string name, int64_t interval, int64_t start,
                                         int64_t end, std::string outputPath, std::vector<uint8_t> members)
    : GroupMeasureStep(std::move(name), interval, start, end, std::move(outputPath),
                       quantity == Quantity::position ? "#step time X Y Z" : "#step time Rmean", std::move(members)),
      quantity_(quantity) {}

void CenterOfMassMeasure::run(Simulation& sim) {
    const int64_t n = sim.particle_count();
    std::vector<double> xyz(3 * n), mass(n);
    sim.get_unwrapped_positions(xyz.data());
    sim.get_masses(mass.data());
    std::array<double, 3> centre{0.0, 0.0, 0.0};
    double total = 0.0;
    int64_t count = 0;
    for (int64_t i = 0; i < n; ++i)
        if (measured(i)) {
            ++count;
            total += mass[i];
            for (int d = 0; d < 3; ++d) centre[d] += mass[i] * xyz[3 * i + d];
        }
    // Massless particles (Brownian inputs) weigh alike: the centre is then their mean position.
    const bool weighted = total > 0.0;
    if (!weighted) {
        centre = {0.0, 0.0, 0.0};
        for (int64_t i = 0; i < n; ++i)
            if (measured(i))
                for (int d = 0; d < 3; ++d) centre[d] += xyz[3 * i + d];
    }
    const double norm = weighted ? total : static_cast<double>(count);
    if (norm > 0.0)
        for (double& c : centre) c /= norm;

    if (quantity_ == Quantity::position) {
        write_line(sim, {centre[0], centre[1], centre[2]});
        return;
    }
    double sum = 0.0;
    for (int64_t i = 0; i < n; ++i)
        if (measured(i)) {
            double d2 = 0.0;
            for (int d = 0; d < 3; ++d) d2 += (xyz[3 * i + d] - centre[d]) * (xyz[3 * i + d] - centre[d]);
            sum += std::sqrt(d2);
        }
    write_line(sim, {count > 0 ? sum / static_cast<double>(count) : 0.0});
}

namespace {

template <CenterOfMassMeasure::Quantity Q>
std::unique_ptr<SimulationStep> make(const StepInput& in) {
    return std::make_unique<CenterOfMassMeasure>(Q, in.name, in.interval(), in.start(), in.end(),
                                                 in.parameters.text("outputFilePath"), in.members);
}

}  // namespace

SimulationStepEntry center_of_mass_position_entry() {
    return {{"GeometricalMeasure", "CenterOfMassPosition"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr}}),
            make<CenterOfMassMeasure::Quantity::position>};
}

SimulationStepEntry mean_radius_entry() {
    return {{"GeometricalMeasure", "MeanRadius"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr}}),
            make<CenterOfMassMeasure::Quantity::meanRadius>};
}

}  // namespace structmd
