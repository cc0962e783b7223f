#pragma once
// The CUDA backend with the parts its engines' units need (cuFFT, cuSOLVER's Cholesky).
#include "backends/cuda/cuda_backend.cuh"
#include "backends/cuda/cuda_cholesky.cuh"
#include "backends/cuda/cuda_fft.cuh"
