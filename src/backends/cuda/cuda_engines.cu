// The CUDA backend's entry points; the engines themselves are instantiated in
// cuda_engine_single.cu and cuda_engine_double.cu.
#include "backends/backend_engines.hpp"
#include "backends/cuda/cuda_check.hpp"

namespace structmd {

std::unique_ptr<Simulation> make_cuda_engine(bool doublePrecision, int device, SimulationSpec spec,
                                             const Logger& log) {
    if (doublePrecision) return make_cuda_engine_double(device, std::move(spec), log);
    return make_cuda_engine_single(device, std::move(spec), log);
}

int cuda_device_count() {
    int count = 0;
    if (cudaGetDeviceCount(&count) != cudaSuccess) {
        cudaGetLastError();  // clear the sticky error so later calls start clean
        return 0;
    }
    return count;
}

std::string cuda_device_name(int device) {
    cudaDeviceProp prop{};
    cuda_check(cudaGetDeviceProperties(&prop, device), "reading device properties");
    return prop.name;
}

}  // namespace structmd
