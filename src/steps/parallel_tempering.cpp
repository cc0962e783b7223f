#include "steps/parallel_tempering.hpp"

namespace structmd {

SimulationStepEntry parallel_tempering_entry() {
    SimulationStepEntry entry{{"ReplicaExchange", "ParallelTempering"},
                              step_parameters({{"temperatures", StepValue::numbers, nullptr, Must::be_finite,
                                                "temperature", "at least two, each > 0: one replica each"},
                                               {"outputFilePath", StepValue::text, nullptr, Must::be_finite, "",
                                                "the attempts and acceptance ratios, written by rank 0"}}),
                              // The replicas exchange whole configurations, so the entry names no group.
                              [](const StepInput& in) -> std::unique_ptr<SimulationStep> {
                                  in.require_all_particles();
                                  return nullptr;
                              }};
    entry.schedulesNothing = true;
    entry.runsReplicas = true;
    return entry;
}

}  // namespace structmd
