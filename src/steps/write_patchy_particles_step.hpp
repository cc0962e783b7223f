#pragma once
// ["WriteStep","WritePatchyParticlesStep"]: as ["WriteStep","WriteStep"], and after the particles the
// patches of every patchy entry (patchy_particles.hpp) whose parent is written, each at its parent's
// position plus its body-frame offset turned by the parent's orientation (next to its parent: a patch
// is not wrapped on its own), with the radius of its patch type. As UAMMD-structured numbers them, the
// patches' types follow the particles' after a gap of one (a patch of type t of the first patchy entry,
// entries in the order of their names, is written as type ntypes + 1 + t; the next entry's start one
// after the last type of the one before). Positions, types and radii only: a format that also writes
// velocities, forces or orientations is refused.
#include <memory>
#include <string>
#include <vector>

#include "forcefield/patchy_particles.hpp"
#include "steps/simulation_step_registry.hpp"
#include "steps/trajectory_writer.hpp"
#include "steps/write_step.hpp"

namespace structmd {

class WritePatchyParticlesStep : public WriteStep {
public:
    // patchy: the patchy entries' configurations, in the order written; firstType: the type number of
    // each one's patch type 0; typeNames: the particles', the gaps (empty) and the patches'.
    WritePatchyParticlesStep(std::string name, int64_t interval, int64_t start, int64_t end, bool wrapped,
                             std::vector<uint8_t> members, std::unique_ptr<TrajectoryWriter> writer,
                             std::vector<std::shared_ptr<const PatchyConfig>> patchy, std::vector<int> firstType,
                             std::vector<std::string> typeNames);

protected:
    void append(Simulation& sim, const std::vector<double>& positions, TrajectoryFrame& frame) override;

private:
    std::vector<std::shared_ptr<const PatchyConfig>> patchy_;
    std::vector<int> firstType_;
    std::vector<double> orientations_;
};

SimulationStepEntry write_patchy_particles_step_entry();

}  // namespace structmd
