#pragma once
// ["GeometricalMeasure","MeanAngularCorrelation"]: one line `step time MAC` per firing, with
// MAC = 1/N sum_i e_z,i(t) . e_z,i(t0), the body z axes now and at the first firing (t0), over the
// particles of the group.
#include <cstdint>
#include <string>
#include <vector>

#include "steps/group_measure_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class MeanAngularCorrelation : public GroupMeasureStep {
public:
    // members: by particle id, 1 for the particles measured; empty for every particle.
    MeanAngularCorrelation(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                           std::vector<uint8_t> members);

protected:
    void run(Simulation& sim) override;

private:
    std::vector<double> referenceAxes_;  // 3n: each particle's body z axis at the first firing
};

SimulationStepEntry mean_angular_correlation_entry();

}  // namespace structmd
