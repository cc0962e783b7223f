// The CUDA side of devices.hpp, in builds with the CUDA backend.
#include "backends/cuda/cuda_check.hpp"
#include "engines/devices.hpp"

namespace structmd {

std::string cuda_backend_unavailable() { return {}; }

int usable_gpu_count() {
    int count = 0;
    if (cudaGetDeviceCount(&count) != cudaSuccess) {
        cudaGetLastError();  // clear the sticky error so later calls start clean
        return 0;
    }
    return count;
}

std::string gpu_name(int device) {
    cudaDeviceProp prop{};
    cuda_check(cudaGetDeviceProperties(&prop, device), "reading device properties");
    return prop.name;
}

}  // namespace structmd
