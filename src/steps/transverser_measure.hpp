#pragma once
// ["TransverserMeasure","Expression"]: each particle's sum over its pairs of an expression of the pair
// (an expression transverser, transverser/expression_sum.hpp), "compute": "r < 1.5" giving
// coordination numbers. With "cutOff" > 0 the pairs closer than it, over a neighbour list; with 0
// (the default) all pairs. The group's particles take part, both of a pair. Header `# id value`;
// each firing a line `# S` (the step) and one row `id sum` per particle of the group.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "simulation/expression_transverser.hpp"
#include "steps/measure_file.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class TransverserMeasure : public SimulationStep {
public:
    TransverserMeasure(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                       ExpressionTransverserSpec spec, std::vector<int64_t> ids);

protected:
    void run(Simulation& sim) override;

private:
    MeasureFile file_;
    ExpressionTransverserSpec spec_;
    std::vector<int64_t> ids_;
};

SimulationStepEntry transverser_measure_entry();

}  // namespace structmd
