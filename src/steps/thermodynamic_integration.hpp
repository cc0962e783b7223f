#pragma once
// ["ThermodynamicMeasure","ThermodynamicIntegration"]: walks the ensemble's lambda through
// lambdaValues, stepLambda steps each, and writes dU/dlambda (summed over the terms of lambda) as it
// goes, as UAMMD-structured does. It fires at the steps that are multiples of intervalStep; with
// s = step - startStep, a firing belongs to block b = s / stepLambda. The first firing of a block
// (while values remain) sets lambda to lambdaValues[b] and writes a line `# <lambda>`; every firing
// writes a line with dU/dlambda at the present state. With intervalStep 1 (as UAMMD-structured runs
// it: it changes lambda at every step) each block starts exactly at its step. The mean of each block
// estimates <dU/dlambda> at that lambda; integrating it over lambda gives the free-energy difference.
// lambdaValues[0] must be the ensemble's lambda at load.
#include <cstdint>
#include <string>
#include <vector>

#include "steps/measure_file.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class ThermodynamicIntegration : public SimulationStep {
public:
    ThermodynamicIntegration(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                             int64_t stepLambda, std::vector<double> values);

protected:
    void run(Simulation& sim) override;

private:
    int64_t start_;
    int64_t stepLambda_;
    std::vector<double> values_;
    int64_t block_ = -1;  // the block of the last firing
    MeasureFile file_;
};

SimulationStepEntry thermodynamic_integration_entry();

}  // namespace structmd
