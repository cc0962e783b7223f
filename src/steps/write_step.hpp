#pragma once
// ["WriteStep","WriteStep"]: writes the particles (all, or a group's), in id order, to
// <outputFilePath>.<outputFormat> at every firing; the formats are in trajectory_writer.hpp.
#include <memory>
#include <string>
#include <vector>

#include "input/description.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"
#include "steps/trajectory_writer.hpp"

namespace structmd {

class WriteStep : public SimulationStep {
public:
    // wrapped: positions wrapped into the box (pbc true) or unwrapped (pbc false). members: by
    // particle id, nonzero for the particles written; empty writes them all.
    // typeNames: the names the frame gives the type numbers; empty takes the simulation's.
    WriteStep(std::string name, int64_t interval, int64_t start, int64_t end, bool wrapped,
              std::vector<uint8_t> members, std::unique_ptr<TrajectoryWriter> writer,
              std::vector<std::string> typeNames = {});

protected:
    void run(Simulation& sim) final;
    // Entries written after the particles (a patchy particle's patches), added to a frame that holds
    // the particles; positions: every particle's, as the frame has them (wrapped or not).
    virtual void append(Simulation& sim, const std::vector<double>& positions, TrajectoryFrame& frame);
    bool written(int64_t id) const { return members_.empty() || members_[static_cast<size_t>(id)]; }

private:
    bool wrapped_;
    std::vector<uint8_t> members_;
    std::vector<std::string> typeNames_;
    std::unique_ptr<TrajectoryWriter> writer_;
    std::vector<double> positions_;  // every particle's, before the selection
    std::vector<int32_t> types_;
    std::vector<double> radii_;
    std::vector<double> velocities_, forces_, orientations_, moments_;  // only for formats that write them
    TrajectoryFrame frame_;
};

// The writer an entry of ["WriteStep", ...] asks for (outputFilePath, outputFormat, append); an
// unknown format is an input error naming parameters.outputFormat, with the known formats.
std::unique_ptr<TrajectoryWriter> trajectory_writer_of(const StepInput& in);
// The parameters of such an entry: the shared ones, outputFilePath, outputFormat, pbc and append.
std::vector<StepParameter> write_step_parameters();

// The registry's entry: outputFilePath, outputFormat (an unknown one is an input error naming
// parameters.outputFormat, with the known formats), pbc and append beside the shared parameters.
SimulationStepEntry write_step_entry();

}  // namespace structmd
