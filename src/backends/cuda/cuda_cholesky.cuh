#pragma once
// The CUDA backend's dense Cholesky factorisation, on cuSOLVER's potrf. Like an FFT it is work the
// host launches itself, on the engine's stream after what the step graphs recorded before it; its
// outcome stays on the device (no wait for the host).
#include <cusolverDn.h>

#include <cstdint>
#include <string>
#include <type_traits>

#include "backends/cuda/cuda_backend.cuh"
#include "core/error.hpp"

namespace structmd {

inline void cusolver_check(cusolverStatus_t status, const char* what) {
    if (status == CUSOLVER_STATUS_SUCCESS) return;
    throw Error(status == CUSOLVER_STATUS_ALLOC_FAILED ? STRUCTMD_ERR_MEMORY : STRUCTMD_ERR_DEVICE,
                std::string(what) + ": cuSOLVER error " + std::to_string(static_cast<int>(status)));
}

template <class R>
class CudaCholesky {
    static constexpr bool kDouble = std::is_same<R, double>::value;

public:
    CudaCholesky(const CudaBackend& backend, int64_t size) : backend_(backend), size_(static_cast<int>(size)) {
        cusolver_check(cusolverDnCreate(&handle_), "creating a cuSOLVER handle");
        int workspace = 0;
        if constexpr (kDouble)
            cusolver_check(cusolverDnDpotrf_bufferSize(handle_, CUBLAS_FILL_MODE_LOWER, size_, nullptr, size_, &workspace),
                           "sizing a Cholesky factorisation");
        else
            cusolver_check(cusolverDnSpotrf_bufferSize(handle_, CUBLAS_FILL_MODE_LOWER, size_, nullptr, size_, &workspace),
                           "sizing a Cholesky factorisation");
        backend_.resize(workspace_, static_cast<size_t>(workspace > 0 ? workspace : 1));
    }
    CudaCholesky(const CudaCholesky&) = delete;
    CudaCholesky& operator=(const CudaCholesky&) = delete;
    ~CudaCholesky() { cusolverDnDestroy(handle_); }

    // As CpuCholesky::factor: L in the lower triangle; *failed (device memory) is potrf's info, 0 when
    // the matrix was positive definite.
    void factor(R* matrix, int* failed) const {
        cusolver_check(cusolverDnSetStream(handle_, static_cast<cudaStream_t>(backend_.host_launch_stream())),
                       "choosing the Cholesky stream");
        const int lwork = static_cast<int>(workspace_.size());
        if constexpr (kDouble)
            cusolver_check(cusolverDnDpotrf(handle_, CUBLAS_FILL_MODE_LOWER, size_, matrix, size_,
                                            workspace_.data(), lwork, failed),
                           "running a Cholesky factorisation");
        else
            cusolver_check(cusolverDnSpotrf(handle_, CUBLAS_FILL_MODE_LOWER, size_, matrix, size_,
                                            workspace_.data(), lwork, failed),
                           "running a Cholesky factorisation");
    }

private:
    const CudaBackend& backend_;
    int size_;
    cusolverDnHandle_t handle_ = nullptr;
    mutable typename CudaBackend::template Buffer<R> workspace_;
};

}  // namespace structmd
