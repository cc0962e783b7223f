#pragma once
// ["ParticlesListMeasure","PotentialMeasure"]: for each listed particle, each forceField entry's
// energy on it and force on it (components and magnitude), with its torque (components and
// magnitude, lab frame; zero for terms that do not act on orientations). Header `# id` then per entry
// `<name>Energy <name>ForceX <name>ForceY <name>ForceZ <name>ForceMod <name>TorqueX <name>TorqueY
// <name>TorqueZ <name>TorqueMod`; each firing a line `# S` (the step) and one row per listed particle.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "steps/measure_file.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class PotentialMeasure : public SimulationStep {
public:
    PotentialMeasure(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                     std::vector<int64_t> ids);

protected:
    void run(Simulation& sim) override;

private:
    std::string outputPath_;
    std::optional<MeasureFile> file_;  // made at the first firing, when the entry names are known
    std::vector<int64_t> ids_;
};

SimulationStepEntry potential_measure_entry();

}  // namespace structmd
