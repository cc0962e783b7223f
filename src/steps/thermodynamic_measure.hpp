#pragma once
// ["ThermodynamicMeasure","ThermodynamicQuantityMeasure"]: one line per firing with step, particle
// number, volume, the energy of each forceField entry (alphabetical), kinetic, potential and total
// energy, temperature T = 2K / (3 N k_B), the virial trace and the pressure (core/thermodynamics.hpp).
#include <optional>
#include <string>

#include "steps/measure_file.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class ThermodynamicMeasure : public SimulationStep {
public:
    ThermodynamicMeasure(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath);

protected:
    void run(Simulation& sim) override;

private:
    std::string outputPath_;
    std::optional<MeasureFile> file_;  // made at the first firing, when the energy terms are known
    bool overdamped_ = false;          // the dynamics of the last row written
};

SimulationStepEntry thermodynamic_measure_entry();

}  // namespace structmd
