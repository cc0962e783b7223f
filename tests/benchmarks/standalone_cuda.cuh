#pragma once
// For the standalone CUDA programs of this folder (no engine linked, so no structmd::Error to throw):
// a failed CUDA call prints what failed and ends the program.
#include <cuda_runtime.h>

#include <cstdio>
#include <cstdlib>

namespace standalone {

inline void check(cudaError_t status, const char* what) {
    if (status != cudaSuccess) {
        std::fprintf(stderr, "%s: %s\n", what, cudaGetErrorString(status));
        std::exit(1);
    }
}

}  // namespace standalone
