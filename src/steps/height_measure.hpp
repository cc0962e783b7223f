#pragma once
// ["GeometricalMeasure","Height"]: at each firing, `step time height`, the mean z of the
// particleNumberAverage highest particles of the group (UAMMD-structured's measure of the height of a
// film or a deposited object). Over the unwrapped positions, so a particle that crossed the top of
// the box stays high rather than reappearing at the bottom.
#include <cstdint>
#include <string>
#include <vector>

#include "steps/measure_file.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class HeightMeasure : public SimulationStep {
public:
    // members: the ids measured, ascending; averaged: how many of the highest are averaged (<= members).
    HeightMeasure(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                  std::vector<int64_t> members, int64_t averaged);

protected:
    void run(Simulation& sim) override;

private:
    MeasureFile file_;
    std::vector<int64_t> members_;
    int64_t averaged_;
};

SimulationStepEntry height_measure_entry();

}  // namespace structmd
