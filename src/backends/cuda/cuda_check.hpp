#pragma once
// The one place that turns a CUDA runtime status into an engine error.
#include <cuda_runtime.h>

#include <string>

#include "core/error.hpp"

namespace structmd {

inline void cuda_check(cudaError_t status, const char* what) {
    if (status == cudaSuccess) return;
    const structmd_status code =
        status == cudaErrorMemoryAllocation ? STRUCTMD_ERR_MEMORY : STRUCTMD_ERR_DEVICE;
    throw Error(code, std::string(what) + ": " + cudaGetErrorString(status));
}

}  // namespace structmd
