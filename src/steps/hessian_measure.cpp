#include "steps/hessian_measure.hpp"

#include <array>
#include <cmath>

#include "core/error.hpp"

namespace structmd {

HessianMeasure::HessianMeasure(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                               Mode mode, int precision, std::vector<int64_t> members)
    : SimulationStep(name, interval, start, end),
      file_("simulationStep." + name, std::move(outputPath), "# Id_i Id_j Hxx Hxy Hxz Hyx Hyy Hyz Hzx Hzy Hzz"),
      mode_(mode),
      precision_(precision),
      members_(std::move(members)) {}

void HessianMeasure::column(Simulation& sim, int64_t id, std::vector<double>& blocks) const {
    if (mode_ == Mode::analytical) {
        sim.probes().hessian_column(id, blocks.data());
        return;
    }
    // Central differences, whose error (h^2 U'''' against rounding eps U' / h) is least near
    // h = eps^(1/3), eps that of the precision the forces are computed in.
    const double eps = sim.description().precision == "double" ? 0x1p-52 : 0x1p-23;
    const double h = std::cbrt(eps);
    const int64_t n = sim.particle_count();
    std::vector<double> forward(3 * n), backward(3 * n);
    for (int a = 0; a < 3; ++a) {
        double displacement[3] = {0.0, 0.0, 0.0};
        displacement[a] = h;
        sim.probes().forces_with_displaced(id, displacement, forward.data());
        displacement[a] = -h;
        sim.probes().forces_with_displaced(id, displacement, backward.data());
        for (int64_t j = 0; j < n; ++j)
            for (int b = 0; b < 3; ++b)
                blocks[9 * j + 3 * a + b] = -(forward[3 * j + b] - backward[3 * j + b]) / (2.0 * h);
    }
}

void HessianMeasure::run(Simulation& sim) {
    std::vector<double> blocks(9 * sim.particle_count());
    std::FILE* out = file_.stream();
    std::fprintf(out, "# step %lld time %.17g\n", static_cast<long long>(sim.current_step()), sim.current_time());
    for (int64_t i : members_) {
        column(sim, i, blocks);
        for (int64_t j : members_) {
            std::fprintf(out, "%lld %lld", static_cast<long long>(i), static_cast<long long>(j));
            for (int k = 0; k < 9; ++k) std::fprintf(out, " %.*f", precision_, blocks[9 * j + k]);
            std::fprintf(out, "\n");
        }
    }
    file_.flush();
}

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    const std::string mode = in.parameters.text("mode");
    if (mode != "Analytical" && mode != "Numerical")
        throw input_error(in.parameters.path("mode"), "expected \"Analytical\" or \"Numerical\", got \"" + mode + "\"");
    const int64_t precision = in.parameters.integer("outputPrecision");
    if (precision > 30)
        throw input_error(in.parameters.path("outputPrecision"),
                          "expected at most 30 decimals, got " + std::to_string(precision));
    return std::make_unique<HessianMeasure>(in.name, in.interval(), in.start(), in.end(),
                                            in.parameters.text("outputFilePath"),
                                            mode == "Analytical" ? HessianMeasure::Mode::analytical
                                                                 : HessianMeasure::Mode::numerical,
                                            static_cast<int>(precision), in.member_ids());
}

}  // namespace

SimulationStepEntry hessian_measure_entry() {
    return {{"MechanicalMeasure", "HessianMeasure"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr},
                             {"mode", StepValue::text, "Analytical", Must::be_finite, "",
                              "\"Analytical\" (exact second derivatives; every term must have them) or "
                              "\"Numerical\" (central differences of the forces)"},
                             {"outputPrecision", StepValue::integer, int64_t{10}, Must::be_non_negative, "",
                              "decimals written after the point, at most 30"}}),
            make};
}

}  // namespace structmd
