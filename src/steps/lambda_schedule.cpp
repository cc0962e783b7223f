#include "steps/lambda_schedule.hpp"

#include "core/error.hpp"

namespace structmd {

double LambdaActivation::lambda_at(int64_t s) const {
    const int64_t k = s / valueSteps_;
    return k < static_cast<int64_t>(values_.size()) ? values_[static_cast<size_t>(k)] : 1.0;
}

double LambdaCycle::lambda_at(int64_t s) const {
    const int64_t activation = activationSteps_ * static_cast<int64_t>(values_.size());
    const int64_t c = s % (activation + measureSteps_ + pauseSteps_);
    if (c < activation) return values_[static_cast<size_t>(c / activationSteps_)];
    return c < activation + measureSteps_ ? 1.0 : 0.0;
}

std::vector<double> read_lambda_values(const StepInput& in) {
    const std::vector<double> values = in.parameters.numbers("lambdaValues");
    for (size_t k = 0; k < values.size(); ++k)
        if (!(values[k] >= 0.0 && values[k] <= 1.0))
            throw input_error(in.parameters.path("lambdaValues") + "[" + std::to_string(k) + "]",
                              "lambda must be in [0, 1], got " + std::to_string(values[k]));
    return values;
}

namespace {

std::unique_ptr<SimulationStep> make_activation(const StepInput& in) {
    return std::make_unique<LambdaActivation>(in.name, in.interval(), in.start(), in.end(),
                                              in.parameters.integer("lambdaValueStep"), read_lambda_values(in));
}

std::unique_ptr<SimulationStep> make_cycle(const StepInput& in) {
    return std::make_unique<LambdaCycle>(in.name, in.interval(), in.start(), in.end(),
                                         in.parameters.integer("activationStep"), in.parameters.integer("measureStep"),
                                         in.parameters.integer("pauseStep"), read_lambda_values(in));
}

constexpr const char* kLambdaValuesNote = "each in [0, 1]";

}  // namespace

SimulationStepEntry lambda_activation_entry() {
    return {{"FlowControl", "LambdaActivation"},
            step_parameters({{"lambdaValueStep", StepValue::integer, nullptr, Must::be_positive, "steps",
                              "steps each value is held"},
                             {"lambdaValues", StepValue::numbers, nullptr, Must::be_finite, "1", kLambdaValuesNote}}),
            make_activation};
}

SimulationStepEntry lambda_cycle_entry() {
    return {{"FlowControl", "LambdaCycle"},
            step_parameters({{"activationStep", StepValue::integer, nullptr, Must::be_positive, "steps",
                              "steps each activation value is held"},
                             {"measureStep", StepValue::integer, nullptr, Must::be_non_negative, "steps",
                              "steps at lambda = 1 after the activation"},
                             {"pauseStep", StepValue::integer, nullptr, Must::be_non_negative, "steps",
                              "steps at lambda = 0 before the next cycle"},
                             {"lambdaValues", StepValue::numbers, nullptr, Must::be_finite, "1", kLambdaValuesNote}}),
            make_cycle};
}

}  // namespace structmd
