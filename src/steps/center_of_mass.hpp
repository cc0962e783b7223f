#pragma once
// The centre of mass and mean radius measures: ["GeometricalMeasure","CenterOfMassPosition"] writes
// `step time X Y Z`, the mass-weighted centre R = sum m_i r_i / sum m_i; ["GeometricalMeasure",
// "MeanRadius"] writes `step time Rmean`, the mean distance 1/N sum_i |r_i - R| of the particles from
// that centre. Both over the unwrapped positions, so a molecule split by the box counts as the whole
// it is (UAMMD-structured takes the wrapped ones), and over a group's members when one is given.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "steps/group_measure_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class CenterOfMassMeasure : public GroupMeasureStep {
public:
    enum class Quantity { position, meanRadius };
    // members: by particle id, 1 for the particles measured; empty for every particle.
    CenterOfMassMeasure(Quantity quantity, std::string name, int64_t interval, int64_t start, int64_t end,
                        std::string outputPath, std::vector<uint8_t> members);

protected:
    void run(Simulation& sim) override;

private:
    Quantity quantity_;
};

SimulationStepEntry center_of_mass_position_entry();
SimulationStepEntry mean_radius_entry();

}  // namespace structmd
