// Builds without the CUDA backend: no GPU is usable, and a CUDA engine cannot be made.
#include "core/error.hpp"
#include "engines/devices.hpp"
#include "engines/engine_instances.hpp"

namespace structmd {

namespace {

Error no_cuda() { return Error(STRUCTMD_ERR_UNSUPPORTED, "this build of structmd has no CUDA backend"); }

}  // namespace

std::string cuda_backend_unavailable() { return "this build of structmd has no CUDA backend"; }
int usable_gpu_count() { return 0; }
std::string gpu_name(int) { throw no_cuda(); }

std::unique_ptr<LocalEngine> make_cuda_engine_single(int, SimulationSpec, const ForceFieldComponents&, const Logger&) {
    throw no_cuda();
}
std::unique_ptr<LocalEngine> make_cuda_engine_mixed(int, SimulationSpec, const ForceFieldComponents&, const Logger&) {
    throw no_cuda();
}
std::unique_ptr<LocalEngine> make_cuda_engine_double(int, SimulationSpec, const ForceFieldComponents&, const Logger&) {
    throw no_cuda();
}

}  // namespace structmd
