#pragma once
// What the machine offers the backends. The CUDA side is answered by cuda_devices.cu in builds with
// the CUDA backend, by no_cuda.cpp in builds without it, and by cuda_module_loader.cpp where the
// backend is a module of its own (STRUCTMD_CUDA_MODULE): the one place that knows which.
#include <string>

namespace structmd {

// Why the CUDA backend cannot be asked for here (not compiled, or its libraries not found); empty when it can.
std::string cuda_backend_unavailable();
int usable_gpu_count();          // 0 without the CUDA backend or without a usable GPU
std::string gpu_name(int device);
int cpu_default_threads();       // what the OpenMP runtime offers

}  // namespace structmd
