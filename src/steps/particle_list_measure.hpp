#pragma once
// ["ParticlesListMeasure", DistancesMeasure | AnglesMeasure | DihedralsMeasure]: for each listed
// pair, triplet or quadruplet of particle ids, the distance |r_j - r_i|, the angle at j between
// r_i - r_j and r_k - r_j (in [0, pi]) or the dihedral of i-j-k-l (IUPAC, in [-pi, pi], as the
// Dihedral bond terms define it), all through minimum images. One line `step time v1 v2 ...` per
// firing, in the order of the table's rows. ["ParticlesListMeasure","ContactsMeasure"] measures the
// distances of its pairs in UAMMD-structured's block layout: a `# step N time T` line, then one
// `id_i id_j r` line per row.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "steps/measure_file.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class ParticleListMeasure : public SimulationStep {
public:
    enum class Layout { line, blocks };  // one line per firing, or a block of one line per row
    // arity 2, 3 or 4: what each row of `ids` lists.
    ParticleListMeasure(int arity, Layout layout, std::string name, int64_t interval, int64_t start, int64_t end,
                        std::string outputPath, std::vector<std::array<int64_t, 4>> ids);

protected:
    void run(Simulation& sim) override;

private:
    int arity_;
    Layout layout_;
    MeasureFile file_;
    std::vector<std::array<int64_t, 4>> ids_;
};

// The rows of the step's table of particle ids (one column per label, at most four), each checked to
// name a particle; ERR_UNSUPPORTED unless the step's group is "All" (the table names the particles).
std::vector<std::array<int64_t, 4>> read_particle_ids(const StepInput& in, const std::vector<std::string>& labels);

// A table cell holding a list of particle ids (a set), each checked to name one of the n particles.
std::vector<int64_t> read_id_list(const input::TrackedNode& list, int64_t n);

SimulationStepEntry distances_measure_entry();
SimulationStepEntry angles_measure_entry();
SimulationStepEntry dihedrals_measure_entry();
SimulationStepEntry contacts_measure_entry();

}  // namespace structmd
