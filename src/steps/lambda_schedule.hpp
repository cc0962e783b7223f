#pragma once
// Simulation steps that drive the ensemble's lambda (["Ensemble","NVTlambda"]) through a schedule,
// as UAMMD-structured's FlowControl steps do. Each firing sets lambda for the step about to be
// integrated, and lambda holds until the next firing (UAMMD-structured requires intervalStep = 1, the
// exact schedule); with s = step - startStep:
//   ["FlowControl","LambdaActivation"]: lambdaValues[s / lambdaValueStep] while
//       s < len(lambdaValues) lambdaValueStep, then 1 for good;
//   ["FlowControl","LambdaCycle"]: with c = s mod (A + measureStep + pauseStep), A = len(lambdaValues)
//       activationStep: lambdaValues[c / activationStep] for c < A, then 1 for measureStep steps,
//       then 0 for pauseStep steps, and again.
// Setting lambda costs one small kernel when it changes, no synchronisation.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class LambdaSchedule : public SimulationStep {
public:
    // The value at s steps after the start.
    virtual double lambda_at(int64_t s) const = 0;

protected:
    LambdaSchedule(std::string name, int64_t interval, int64_t start, int64_t end)
        : SimulationStep(std::move(name), interval, start, end), start_(start) {}
    void run(Simulation& sim) override { sim.set_lambda(lambda_at(sim.current_step() - start_)); }

private:
    int64_t start_;
};

class LambdaActivation : public LambdaSchedule {
public:
    LambdaActivation(std::string name, int64_t interval, int64_t start, int64_t end, int64_t valueSteps,
                     std::vector<double> values)
        : LambdaSchedule(std::move(name), interval, start, end), valueSteps_(valueSteps), values_(std::move(values)) {}
    double lambda_at(int64_t s) const override;

private:
    int64_t valueSteps_;
    std::vector<double> values_;
};

class LambdaCycle : public LambdaSchedule {
public:
    LambdaCycle(std::string name, int64_t interval, int64_t start, int64_t end, int64_t activationSteps,
                int64_t measureSteps, int64_t pauseSteps, std::vector<double> values)
        : LambdaSchedule(std::move(name), interval, start, end),
          activationSteps_(activationSteps),
          measureSteps_(measureSteps),
          pauseSteps_(pauseSteps),
          values_(std::move(values)) {}
    double lambda_at(int64_t s) const override;

private:
    int64_t activationSteps_, measureSteps_, pauseSteps_;
    std::vector<double> values_;
};

// lambdaValues as a step reads them: each in [0, 1], else ERR_INPUT at <entry>.parameters.lambdaValues[k].
std::vector<double> read_lambda_values(const StepInput& in);

SimulationStepEntry lambda_activation_entry();
SimulationStepEntry lambda_cycle_entry();

}  // namespace structmd
