#pragma once
// ["GeometricalMeasure","MeanSquareDisplacement"]: one line `step time msd` per firing, with
// msd = 1/N sum_i |r_i(t) - r_i(t0)|^2 over the unwrapped positions (box crossings counted), t0 the
// first firing. With a group, over its members only.
#include <cstdint>
#include <string>
#include <vector>

#include "steps/group_measure_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class MeanSquareDisplacement : public GroupMeasureStep {
public:
    // members: by particle id, 1 for the particles measured; empty for every particle.
    MeanSquareDisplacement(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                           std::vector<uint8_t> members);

protected:
    void run(Simulation& sim) override;

private:
    std::vector<double> reference_;  // unwrapped positions at the first firing; empty before it
};

SimulationStepEntry mean_square_displacement_entry();

}  // namespace structmd
