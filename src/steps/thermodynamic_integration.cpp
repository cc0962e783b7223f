#include "steps/thermodynamic_integration.hpp"

#include "core/error.hpp"
#include "steps/lambda_schedule.hpp"

namespace structmd {

ThermodynamicIntegration::ThermodynamicIntegration(std::string name, int64_t interval, int64_t start, int64_t end,
                                                   std::string outputPath, int64_t stepLambda, std::vector<double> values)
    : SimulationStep(name, interval, start, end),
      start_(start),
      stepLambda_(stepLambda),
      values_(std::move(values)),
      file_("simulationStep." + name, std::move(outputPath), "# dU/dlambda") {}

void ThermodynamicIntegration::run(Simulation& sim) {
    const int64_t block = (sim.current_step() - start_) / stepLambda_;
    if (block >= static_cast<int64_t>(values_.size())) return;  // every value done: the file is complete
    std::FILE* out = file_.stream();
    if (block != block_) {
        block_ = block;
        sim.set_lambda(values_[static_cast<size_t>(block)]);
        std::fprintf(out, "# %.17g\n", sim.lambda());
    }
    std::fprintf(out, "%.17g\n", sim.probes().lambda_derivative());
    file_.flush();
}

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    std::vector<double> values = read_lambda_values(in);
    const double initial = in.system.lambda.value_or(1.0);
    if (values.front() != initial)
        throw input_error(in.parameters.path("lambdaValues") + "[0]",
                          "must be the ensemble's lambda (" + std::to_string(initial) + "), got " +
                              std::to_string(values.front()));
    return std::make_unique<ThermodynamicIntegration>(in.name, in.interval(), in.start(), in.end(),
                                                      in.parameters.text("outputFilePath"),
                                                      in.parameters.integer("stepLambda"), std::move(values));
}

}  // namespace

SimulationStepEntry thermodynamic_integration_entry() {
    return {{"ThermodynamicMeasure", "ThermodynamicIntegration"},
            step_parameters({{"outputFilePath", StepValue::text, nullptr},
                             {"stepLambda", StepValue::integer, nullptr, Must::be_positive, "steps",
                              "steps each lambda value is held"},
                             {"lambdaValues", StepValue::numbers, nullptr, Must::be_finite, "1",
                              "each in [0, 1]; the first must be the ensemble's lambda"}}),
            make};
}

}  // namespace structmd
