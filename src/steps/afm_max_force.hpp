#pragma once
// ["FlowControl","AFMMaxForce"]: ends the step call (Simulation::request_stop) once every AFM tip of
// the step's group has pressed on its cantilever with a force K (z_tip - z_chip) >= maxForce at some
// firing, each tip's crossing remembered, as UAMMD-structured stops an indentation experiment at
// a set force. It stops one call, the one where the last tip gets there; later calls step on. The
// tips are those of the input's first AFM entry (read_afm_tips).
#include <cstdint>
#include <string>
#include <vector>

#include "steps/afm_measure.hpp"
#include "steps/simulation_step.hpp"
#include "steps/simulation_step_registry.hpp"

namespace structmd {

class AfmMaxForce : public SimulationStep {
public:
    AfmMaxForce(std::string name, int64_t interval, int64_t start, int64_t end, double maxForce,
                std::vector<AfmMeasure::Tip> tips);

protected:
    void run(Simulation& sim) override;

private:
    double maxForce_;
    std::vector<AfmMeasure::Tip> tips_;
    std::vector<bool> reached_;  // by tip
};

SimulationStepEntry afm_max_force_entry();

}  // namespace structmd
