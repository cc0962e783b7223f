#pragma once
// ["MechanicalMeasure","ForceBetweenSetsMeasure"]: the force each named set of particles exerts on
// each other set, the sum over receivers i in the one and sources j in the other of the pair force
// f_(j->i) (Simulation::pair_forces_on). One line `from to Fx Fy Fz` per ordered pair of sets, each
// firing's lines after a line `# step S time T`.
#include <cstdint>
#include <string>
#include <vector>

#include "steps/measure_file.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class ForceBetweenSetsMeasure : public SimulationStep {
public:
    struct Set {
        std::string name;
        std::vector<int64_t> ids;
    };

    ForceBetweenSetsMeasure(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                            std::vector<Set> sets);

    bool needs_pair_forces() const override { return true; }

protected:
    void run(Simulation& sim) override;

private:
    MeasureFile file_;
    std::vector<Set> sets_;
};

SimulationStepEntry force_between_sets_measure_entry();

}  // namespace structmd
