#pragma once
// What the machine offers the backends. The CUDA side is answered by cuda_devices.cu in builds with
// the CUDA backend and by no_cuda.cpp in builds without it: the one place that knows which.
#include <string>

namespace structmd {

bool cuda_backend_compiled();
int usable_gpu_count();          // 0 without the CUDA backend or without a usable GPU
std::string gpu_name(int device);
int cpu_default_threads();       // what the OpenMP runtime offers

}  // namespace structmd
