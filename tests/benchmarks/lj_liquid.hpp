// The Lennard-Jones liquid that the benchmarks run (the system of LAMMPS's bench/in.lj): an fcc
// lattice at reduced density 0.8442 that melts at T = 1.44, LJ 12-6 with epsilon = sigma = mass = 1
// cut at 2.5 sigma, NVE velocity Verlet; many copies of it as batches; and a melt of bead chains. Also the small helpers both programs share: reading the
// engine's JSON reports and taking a median.
#ifndef STRUCTMD_BENCHMARKS_LJ_LIQUID_HPP
#define STRUCTMD_BENCHMARKS_LJ_LIQUID_HPP

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "structmd.h"

namespace structmd::benchmarks {

constexpr double kDensity = 0.8442;
constexpr double kTemperature = 1.44;
constexpr double kCutOff = 2.5;  // in sigma

struct LjLiquid {
    int64_t cells = 1;           // fcc cells per box edge: 4 cells^3 particles
    double timeStep = 0.005;     // tau
    double skin = 0.3;           // sigma, added to the cutoff for the Verlet list
    bool shiftEnergy = false;    // the LJ entry's "shift": energy continuous at the cutoff
    bool asExpression = false;   // LJ as ["NonBonded","Expression"] instead of LennardJonesType1
    int64_t scheduleSteps = 0;   // the schedule's length: structmd_step cannot go past it
    int64_t batches = 1;         // independent copies of the liquid in one box, batchId 0, 1, ...
};

// Chains of beads on a simple cubic lattice at density 0.85, one chain per lattice row along x, so
// `chains` of `beads` fill a box of beads x sqrt(chains)^2 sites (chains must be a square):
// harmonic bonds (K = 100, r0 = 1), KratkyPorod bending (K = 2), WCA between every pair not
// bonded (a nonExcluded list that excludes bonded neighbours), Langevin BBK at T = 1, gamma = 1.
struct BeadChains {
    int64_t chains = 10000;
    int64_t beads = 100;
    double timeStep = 0.005;
    double skin = 0.3;
    int64_t scheduleSteps = 0;
};

// fcc holds 4 particles per cubic cell: the number of cells per edge whose 4 k^3 is nearest to
// the requested particle count.
int64_t cells_per_edge(int64_t requested_particles);

// The whole input document. The state has no velocity column, so the engine draws velocities from
// Maxwell-Boltzmann at kTemperature (seed 1). Built with std::to_chars into one reserved string,
// about 57 bytes per particle: 16 million particles make 0.9 GB of text in about 4 s on a 2-core
// machine, where the engine's parse of it then takes about 3 s per million particles.
std::string lj_liquid_input(const LjLiquid& liquid);

std::string bead_chains_input(const BeadChains& melt);

// structmd_create options for a backend ("auto", "cpu", "cuda"), a precision and a CPU thread count
// (0: the engine's default).
// pairTraversal: the engine option "pair_traversal" (auto, clusters or particles).
std::string create_options(const std::string& backend, const std::string& precision, int threads,
                           const std::string& pairTraversal = "auto");

nlohmann::json engine_info(const structmd_sim* sim);      // structmd_get_info, parsed
nlohmann::json engine_counters(structmd_sim* sim);        // structmd_get_counters, parsed

double median(std::vector<double> values);

// Opens path for the rows of a table and writes its header; false (with a message) if it cannot.
bool open_csv(std::ofstream& csv, const std::string& path, const std::string& header);

}  // namespace structmd::benchmarks

#endif  // STRUCTMD_BENCHMARKS_LJ_LIQUID_HPP
