#pragma once
// ["GeometricalMeasure","GyrationRadius"]: one line `step time Rg` per firing, with
// Rg^2 = 1/N sum_i |r_i - r_mean|^2 over the unwrapped positions (every particle weighs the same), so
// a molecule split across the boundary counts as the whole it is. With a group, over its members only.
#include <cstdint>
#include <string>
#include <vector>

#include "steps/group_measure_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class GyrationRadius : public GroupMeasureStep {
public:
    // members: by particle id, 1 for the particles measured; empty for every particle.
    GyrationRadius(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                   std::vector<uint8_t> members);

protected:
    void run(Simulation& sim) override;
};

SimulationStepEntry gyration_radius_entry();

}  // namespace structmd
