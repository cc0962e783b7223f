#pragma once
// Page-locked host memory for the copies between the caller's arrays and the device. A copy from
// pageable memory goes through a driver bounce buffer and blocks the host; from pinned memory it
// runs at full speed and an upload returns at once. With unified addressing (every 64-bit CUDA
// platform) kernels also read and write it directly through the same pointer: the subset calls of a
// coupling loop gather into it and scatter from it without a copy. Reused call after call: it
// grows, never shrinks.
#include <cuda_runtime.h>

#include <string>

#include "backends/cuda/cuda_check.hpp"

namespace structmd {

template <class T>
class PinnedStaging {
public:
    PinnedStaging() = default;
    PinnedStaging(const PinnedStaging&) = delete;
    PinnedStaging& operator=(const PinnedStaging&) = delete;
    ~PinnedStaging() {
        if (inFlight_) cudaEventSynchronize(copied_);
        if (copied_) cudaEventDestroy(copied_);
        if (data_) cudaFreeHost(data_);
    }

    // Room for n values, writable once the device has finished reading the last ones.
    T* reserve(size_t n) {
        wait_for_upload();
        if (n > capacity_) {
            if (data_) cudaFreeHost(data_);
            data_ = nullptr;
            capacity_ = 0;
            const cudaError_t status = cudaMallocHost(&data_, n * sizeof(T));
            if (status != cudaSuccess) {
                cudaGetLastError();
                data_ = nullptr;
                cuda_check(status, ("allocating " + std::to_string(n * sizeof(T)) + " bytes of pinned host memory").c_str());
            }
            capacity_ = n;
        }
        return data_;
    }
    T* data() { return data_; }
    const T* data() const { return data_; }

    // Work queued on stream (a copy, a kernel) reads from here: the next reserve waits for it.
    void mark_read_by(cudaStream_t stream) {
        if (!copied_) cuda_check(cudaEventCreateWithFlags(&copied_, cudaEventDisableTiming), "creating an event");
        cuda_check(cudaEventRecord(copied_, stream), "recording an event");
        inFlight_ = true;
    }

private:
    void wait_for_upload() {
        if (!inFlight_) return;
        cuda_check(cudaEventSynchronize(copied_), "waiting for the device to read pinned memory");
        inFlight_ = false;
    }

    T* data_ = nullptr;
    size_t capacity_ = 0;
    cudaEvent_t copied_ = nullptr;
    bool inFlight_ = false;
};

}  // namespace structmd
