#pragma once
// ["ExperimentMeasures","AFMMeasure"]: what an AFM experiment records, for each row of the input's
// first AFM entry (["AFM","SphericalTip"] or ["AFM","SphericallyBluntedConicTip"]: their chips and
// springs are alike) whose tip is in the step's group: the indentation X = z_tip - R_tip and
// the cantilever force F = K (z_tip - z_chip) (K the spring along z, the chip where the term puts it at
// this step). One line `step time X_0 F_0 X_1 F_1 ...` per firing; with verbose, per row
// `chip_z tip_z deflection tipForce_z sampleForce_z F` instead (deflection = z_tip - z_chip; the forces
// the whole force field exerts on the tip and on its sample).
#include <cstdint>
#include <string>
#include <vector>

#include "forcefield/afm_tip.hpp"
#include "steps/measure_file.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class AfmMeasure : public SimulationStep {
public:
    struct Tip {
        int64_t id;
        double radius;
        AfmParams<SphericalTipPotential, double> afm;  // the row's spring and chip
        std::vector<int64_t> sample;
    };
    AfmMeasure(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath, bool verbose,
               std::vector<Tip> tips);

protected:
    void run(Simulation& sim) override;

private:
    MeasureFile file_;
    bool verbose_;
    std::vector<Tip> tips_;
};

// The tips of the input's first AFM entry that are in the step's group, as UAMMD-structured takes
// them; an input error at the entry's path when it has no AFM entry or the group holds no tip.
std::vector<AfmMeasure::Tip> read_afm_tips(const StepInput& in);

SimulationStepEntry afm_measure_entry();

}  // namespace structmd
