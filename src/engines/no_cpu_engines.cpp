// Builds without the CPU engines (STRUCTMD_CPU_ENGINES=OFF, CUDA only): a CPU engine cannot be made.
#include "core/error.hpp"
#include "engines/engine_instances.hpp"

namespace structmd {

namespace {

Error no_cpu_engines() {
    return Error(STRUCTMD_ERR_UNSUPPORTED,
                 "option \"backend\": this build of structmd has no CPU engines (built with STRUCTMD_CPU_ENGINES=OFF)");
}

}  // namespace

std::unique_ptr<LocalEngine> make_cpu_engine_single(int, SimulationSpec, const ForceFieldComponents&, const Logger&) {
    throw no_cpu_engines();
}
std::unique_ptr<LocalEngine> make_cpu_engine_mixed(int, SimulationSpec, const ForceFieldComponents&, const Logger&) {
    throw no_cpu_engines();
}
std::unique_ptr<LocalEngine> make_cpu_engine_double(int, SimulationSpec, const ForceFieldComponents&, const Logger&) {
    throw no_cpu_engines();
}

}  // namespace structmd
