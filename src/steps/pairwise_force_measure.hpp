#pragma once
// ["MechanicalMeasure","PairwiseForceMeasure"]: the forces of the force field resolved by pair. Mode
// "Pairwise_force" writes, for each particle i of the group (the receiver) and each other particle j
// of the group that exerts a nonzero force on it, the line `j i Fx Fy Fz` (From, To): pair terms
// give their pair force, bonds their forces split into central pair forces. Mode "Total_force"
// writes `i Fx Fy Fz`, the force field's whole force on each particle of the group. Each firing's
// lines follow a line `# step S time T`.
#include <cstdint>
#include <string>
#include <vector>

#include "steps/measure_file.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class PairwiseForceMeasure : public SimulationStep {
public:
    enum class Mode { pairwise, total };

    // members: the group's particle ids in ascending order.
    PairwiseForceMeasure(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                         Mode mode, std::vector<int64_t> members);

    bool needs_pair_forces() const override { return mode_ == Mode::pairwise; }

protected:
    void run(Simulation& sim) override;

private:
    MeasureFile file_;
    Mode mode_;
    std::vector<int64_t> members_;
};

SimulationStepEntry pairwise_force_measure_entry();

}  // namespace structmd
