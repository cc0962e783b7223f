#pragma once
// ["MechanicalMeasure","StressMeasure"]: the stress of each particle from the non-bonded pair terms,
// sigma_i = S_i / V_i, written as a block per firing:
//
//     #step N
//     id V sxx sxy sxz syx syy syz szx szy szz     (one line per particle, in id order)
//
// S_i = 1/2 sum_j (r_i - r_j) (x) F_ij is the particle's share of the pair virial (Simulation::
// get_pair_virials; positive under compression, the sign of the pressure). V_i is the particle's volume
// estimated as UAMMD-structured's StressMeasure does, from the other particles within radiusCutOff
// (minimum image): V_i = 4/3 pi R_i^3 with R_i = 1/2 sum_j r_ij^-1 / sum_j r_ij^-2, half the distance
// to the neighbours weighted by 1/r^2 (so the nearest dominate). A particle with no other particle
// within radiusCutOff has no volume: V_i = 0, and its stress is 0 when S_i is (no pair force, as when
// radiusCutOff covers every pair cutoff), else nan. With a group, only its members get a line (their
// volumes still count every particle around them).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "steps/group_measure_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class StressMeasure : public GroupMeasureStep {
public:
    // members: by particle id, 1 for the particles written; empty for every particle.
    StressMeasure(std::string name, int64_t interval, int64_t start, int64_t end, std::string outputPath,
                  double radiusCutOff, std::vector<uint8_t> members);

protected:
    void run(Simulation& sim) override;

private:
    double radiusCutOff_;
};

// V_i as above for positions xyz (3n, inside the box [-L/2, L/2)); radiusCutOff must be shorter than
// half of every box edge, so each pair is seen once, through its minimum image.
std::vector<double> neighbour_volumes(const std::vector<double>& xyz, const std::array<double, 3>& box,
                                      double radiusCutOff);

SimulationStepEntry stress_measure_entry();

}  // namespace structmd
