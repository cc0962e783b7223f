#pragma once
// ["TopologicalMeasures","PatchPolymers"]: the polymers that dynamically bonded patchy particles form
// (a ["PatchyParticles","DynamicallyBondedPatchyParticles"] entry whose monomers carry one start and
// one end patch each), and, with a ["PatchyParticles","PatchyParticles"] entry of
// ["SurfacePatches","Linker"] patches, which monomers are on the surface (their linker patch's energy
// below surfaceEnergyThreshold). At each firing the step reads the bonds (SimulationProbes::patch_bonds)
// and, with a surface, the monomers' positions and orientations, compares them with the previous
// firing's and turns the differences into events (a start patch unbonded, bonded, a monomer reaching
// or leaving the surface), which update the polymers (patch_polymer_tracker.hpp). It writes, at
// outputFilePath followed by each name: PolymerDistribution.dat, TransitionMatrix.dat, with a surface
// SurfacePolymerDistribution.dat and FractionMonomersInSurface.dat, and with writeEvents the binary
// Events.dat. UAMMD-structured records the events at every step; here they are what changed between
// two firings (intervalStep 1 sees every step's).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "forcefield/patchy_particles.hpp"
#include "steps/measure_file.hpp"
#include "steps/patch_polymer_tracker.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class PatchPolymers : public SimulationStep {
public:
    // The monomers (particle ids, ascending) and, by monomer, its start patch in the bonded entry
    // and its linker patch in the surface entry (when there is one).
    struct Monomers {
        std::vector<int64_t> ids;
        std::vector<int> startPatch;
        std::vector<int> linkerPatch;
    };
    struct Files {
        std::string prefix;  // outputFilePath
        bool writeEvents;
    };

    PatchPolymers(std::string name, int64_t interval, int64_t start, int64_t end, Files files, int maxLen,
                  std::string bondedEntry, std::shared_ptr<const PatchyConfig> bonded, int endType,
                  std::shared_ptr<const PatchyConfig> surface, double surfaceEnergyThreshold, Monomers monomers);

protected:
    void run(Simulation& sim) override;

private:
    // By monomer: the monomer its start patch is bonded to (an end patch of another monomer of the
    // group), or -1; bonds to particles outside the group are not counted.
    std::vector<int> start_partners(Simulation& sim) const;
    std::vector<bool> on_surface(Simulation& sim) const;
    void write_event(int64_t step, int monomer, int type, int64_t info);
    void write_outputs(int64_t step);

    int maxLen_;
    std::string bondedEntry_;
    std::shared_ptr<const PatchyConfig> bonded_;
    int endType_;
    std::shared_ptr<const PatchyConfig> surface_;  // null without a surface
    double threshold_;
    Monomers monomers_;
    std::vector<int> localOf_;  // by particle id: its monomer number, or -1
    MeasureFile distribution_, transitions_;
    std::optional<MeasureFile> surfaceDistribution_, surfaceFraction_, events_;
    // What the previous firing saw; no tracker before the first firing.
    std::optional<PatchPolymerTracker> tracker_;
    std::vector<int> partners_;
    std::vector<bool> surfaceNow_;
};

SimulationStepEntry patch_polymers_entry();

}  // namespace structmd
