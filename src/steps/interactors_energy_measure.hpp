#pragma once
// ["ThermodynamicMeasure","InteractorsListEnergyMeasure"]: one line `step time E1 E2 ...` per firing,
// the energy of each listed force-field interaction entry (interactorsList; every interaction entry,
// in document order, when the list is absent or empty), as structmd_get_energy gives it.
#include <cstdint>
#include <string>
#include <vector>

#include "steps/measure_file.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class InteractorsEnergyMeasure : public SimulationStep {
public:
    InteractorsEnergyMeasure(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                             std::vector<std::string> terms);

protected:
    void run(Simulation& sim) override;

private:
    MeasureFile file_;
    std::vector<std::string> terms_;
};

SimulationStepEntry interactors_energy_measure_entry();

}  // namespace structmd
