#pragma once
// ["Simulation","Backup"] (in the system section): a checkpoint every backupIntervalStep steps,
// each replacing the last one atomically (structmd_save_checkpoint).
#include <string>

#include "steps/simulation_step.hpp"

namespace structmd {

class BackupStep : public SimulationStep {
public:
    BackupStep(int64_t interval, int64_t start, int64_t end, std::string path)
        : SimulationStep("backup", interval, start, end), path_(std::move(path)) {}

protected:
    void run(Simulation& sim) override { sim.save_checkpoint(path_); }

private:
    std::string path_;
};

}  // namespace structmd
