#pragma once
// ["GeometricalMeasure","DistanceBetweenCentersOfMass"]: for each row of its table, the distance
// between the centres of mass of two sets of particles ("idSet_i", "idSet_j"). One line
// `step time d_0 d_1 ...` per firing. Each centre is taken as the Set components take it
// (set_interaction.hpp): members unwrapped next to the set's first member, mass-weighted (equal
// weights for a massless set); the distance is that of the minimum image.
#include <cstdint>
#include <string>
#include <vector>

#include "steps/measure_file.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class DistanceBetweenCentersOfMass : public SimulationStep {
public:
    struct Pair {
        std::vector<int64_t> first, second;
    };
    DistanceBetweenCentersOfMass(std::string name, int64_t interval, int64_t start, int64_t end,
                                 std::string outputPath, std::vector<Pair> pairs);

protected:
    void run(Simulation& sim) override;

private:
    MeasureFile file_;
    std::vector<Pair> pairs_;
};

SimulationStepEntry distance_between_centers_of_mass_entry();

}  // namespace structmd
