#pragma once
// ["TransverserMeasure", ...]: every firing, each particle's values of a transverser run over its
// pairs, one row per particle of the group. Header `# id value` (`# id value_0 value_1 ...` for a
// transverser of several values per particle); each firing a line `# S` (the step) and one row
// `id values...` per particle of the group, in id order.
//
// ["TransverserMeasure","Expression"]: each particle's sum over its pairs of an expression of the pair
// (an expression transverser, transverser/expression_sum.hpp), "compute": "r < 1.5" giving
// coordination numbers. With "cutOff" > 0 the pairs closer than it, over a neighbour list; with 0
// (the default) all pairs. The group's particles take part, both of a pair. The Plugin variant, a
// transverser a plugin registered, is plugin_transverser_measure.hpp.
#include <cstdint>
#include <string>
#include <vector>

#include "simulation/expression_transverser.hpp"
#include "steps/measure_file.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class TransverserMeasure : public SimulationStep {
public:
    // values: the numbers per particle; ids: the particles written, ascending.
    TransverserMeasure(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                       int values, std::vector<int64_t> ids);

protected:
    void run(Simulation& sim) final;
    // Every particle's values (values x n numbers, id order) for the current state.
    virtual void traverse(Simulation& sim, double* perParticle) = 0;

private:
    MeasureFile file_;
    int values_;
    std::vector<int64_t> ids_;
};

class ExpressionTransverserMeasure final : public TransverserMeasure {
public:
    ExpressionTransverserMeasure(std::string name, int64_t interval, int64_t start, int64_t end,
                                 std::string outputPath, ExpressionTransverserSpec spec, std::vector<int64_t> ids);

private:
    void traverse(Simulation& sim, double* perParticle) override;

    ExpressionTransverserSpec spec_;
};

SimulationStepEntry transverser_measure_entry();

}  // namespace structmd
