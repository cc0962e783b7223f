#pragma once
// The magnetization measures: ["MagneticMeasure","MeasureTotalMagnetization"] writes
// `step time Mx My Mz`, the sum of the particles' magnetic moments mu_i (lab frame);
// ["MagneticMeasure","MeasureMeanMagnetization"] writes the same sum divided by sum_i |mu_i|, the
// mean alignment of the moments (1 when all point alike). Over a group's members when one is given.
#include <cstdint>
#include <string>
#include <vector>

#include "steps/group_measure_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class MagnetizationMeasure : public GroupMeasureStep {
public:
    // members: by particle id, 1 for the particles measured; empty for every particle.
    MagnetizationMeasure(bool mean, std::string name, int64_t interval, int64_t start, int64_t end,
                         std::string outputPath, std::vector<uint8_t> members);

protected:
    void run(Simulation& sim) override;

private:
    bool mean_;
};

SimulationStepEntry total_magnetization_entry();
SimulationStepEntry mean_magnetization_entry();

}  // namespace structmd
