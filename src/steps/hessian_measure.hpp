#pragma once
// ["MechanicalMeasure","HessianMeasure"]: the Hessian of the potential energy, d2U / dx_i dx_j, as
// one 3x3 block per pair of the group's particles (i and j both run over the group). Mode
// "Analytical" takes exact second derivatives from the engine (every term differentiated in dual
// numbers); "Numerical" differentiates the forces by central differences. The file holds the lines
// `id_i id_j Hxx Hxy Hxz Hyx Hyy Hyz Hzx Hzy Hzz` (row: i's axis, column: j's), each firing's block
// after a line `# step S time T`.
#include <cstdint>
#include <string>
#include <vector>

#include "steps/measure_file.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class HessianMeasure : public SimulationStep {
public:
    enum class Mode { analytical, numerical };

    // members: the group's particle ids in ascending order; precision: decimals written.
    HessianMeasure(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath, Mode mode,
                   int precision, std::vector<int64_t> members);

    bool needs_hessian() const override { return mode_ == Mode::analytical; }

protected:
    void run(Simulation& sim) override;

private:
    // Blocks of particle id against every particle (9n), by mode.
    void column(Simulation& sim, int64_t id, std::vector<double>& blocks) const;

    MeasureFile file_;
    Mode mode_;
    int precision_;
    std::vector<int64_t> members_;
};

SimulationStepEntry hessian_measure_entry();

}  // namespace structmd
