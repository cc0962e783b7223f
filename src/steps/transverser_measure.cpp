#include "steps/transverser_measure.hpp"

namespace structmd {

namespace {

std::string header_of(int values) {
    if (values == 1) return "# id value";
    std::string header = "# id";
    for (int k = 0; k < values; ++k) header += " value_" + std::to_string(k);
    return header;
}

}  // namespace

TransverserMeasure::TransverserMeasure(std::string name, int64_t interval, int64_t start, int64_t end,
                                       std::string outputPath, int values, std::vector<int64_t> ids)
    : SimulationStep(name, interval, start, end),
      file_("simulationStep." + name, std::move(outputPath), header_of(values)),
      values_(values),
      ids_(std::move(ids)) {}

void TransverserMeasure::run(Simulation& sim) {
    std::vector<double> perParticle(static_cast<size_t>(sim.particle_count() * values_));
    traverse(sim, perParticle.data());
    std::FILE* out = file_.stream();
    std::fprintf(out, "# %lld\n", static_cast<long long>(sim.current_step()));
    for (int64_t id : ids_) {
        std::fprintf(out, "%lld", static_cast<long long>(id));
        for (int k = 0; k < values_; ++k) std::fprintf(out, " %.17g", perParticle[id * values_ + k]);
        std::fputc('\n', out);
    }
    file_.flush();
}

ExpressionTransverserMeasure::ExpressionTransverserMeasure(std::string name, int64_t interval, int64_t start,
                                                           int64_t end, std::string outputPath,
                                                           ExpressionTransverserSpec spec, std::vector<int64_t> ids)
    : TransverserMeasure(std::move(name), interval, start, end, std::move(outputPath), 1, std::move(ids)),
      spec_(std::move(spec)) {}

void ExpressionTransverserMeasure::traverse(Simulation& sim, double* perParticle) {
    sim.probes().expression_sum(spec_, perParticle);
}

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    ExpressionTransverserSpec spec = make_expression_transverser(
        in.parameters.text("compute"), in.parameters.path("compute"), in.parameters.number("cutOff"), in.group);
    return std::make_unique<ExpressionTransverserMeasure>(in.name, in.interval(), in.start(), in.end(),
                                                          in.parameters.text("outputFilePath"), std::move(spec),
                                                          in.member_ids());
}

}  // namespace

SimulationStepEntry transverser_measure_entry() {
    return {{"TransverserMeasure", "Expression"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr},
                             {"compute", StepValue::text, nullptr, Must::be_finite, "",
                              "an expression of r, dx, dy, dz, type_i, type_j, charge_i, charge_j, radius_i, "
                              "radius_j, mass_i, mass_j"},
                             {"cutOff", StepValue::number, 0.0, Must::be_non_negative, "length",
                              "0: all pairs"}}),
            make};
}

}  // namespace structmd
