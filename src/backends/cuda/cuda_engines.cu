#include "backends/backend_engines.hpp"
#include "backends/cuda/cuda_backend.cuh"
#include "simulation/engine.hpp"

namespace structmd {

std::unique_ptr<Simulation> make_cuda_engine(bool doublePrecision, int device, SimulationSpec spec,
                                             const Logger& log) {
    if (doublePrecision) return std::make_unique<Engine<CudaBackend, double>>(std::move(spec), log, device);
    return std::make_unique<Engine<CudaBackend, float>>(std::move(spec), log, device);
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
