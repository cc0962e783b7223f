// The CUDA backend's entry points; the engines themselves are instantiated in
// cuda_engine_single.cu, cuda_engine_mixed.cu and cuda_engine_double.cu.
#include "backends/backend_engines.hpp"
#include "backends/cuda/cuda_check.hpp"

namespace structmd {

std::unique_ptr<Simulation> make_cuda_engine(const std::string& precision, int device, SimulationSpec spec,
                                             const Logger& log) {
    if (precision == "double") return make_cuda_engine_double(device, std::move(spec), log);
    if (precision == "mixed") return make_cuda_engine_mixed(device, std::move(spec), log);
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
