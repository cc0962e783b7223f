#include "steps/sort_step.hpp"

namespace structmd {

namespace {

std::unique_ptr<SimulationStep> make(const StepInput& in) {
    in.log.info(in.path + ": particles are kept sorted by cell at every neighbour-list build; SortStep adds nothing");
    return nullptr;
}

}  // namespace

SimulationStepEntry sort_step_entry() { return {{"UtilsStep", "SortStep"}, step_parameters({}), make, {}, true}; }

}  // namespace structmd
