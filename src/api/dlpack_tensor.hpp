#pragma once
// A DLPack tensor over memory the engine owns (structmd_get_view, structmd_traverse_view): the
// tensor owns only its description (shape and strides), released by its deleter, which touches no
// handle; the data stay the engine's.
#include <dlpack/dlpack.h>

#include <cstdint>
#include <memory>

namespace structmd::api {

// A tensor of `ndim` (1 or 2) dimensions of reals of realSize bytes at `data`, on CUDA device
// `device` or in host memory (device < 0); shape and strides in elements.
inline DLManagedTensor* make_engine_tensor(const void* data, int device, int realSize, int ndim,
                                           const int64_t shape[2], const int64_t strides[2]) {
    struct Tensor {
        DLManagedTensor managed{};
        int64_t shape[2] = {};
        int64_t strides[2] = {};
    };
    auto tensor = std::make_unique<Tensor>();
    for (int k = 0; k < ndim; ++k) {
        tensor->shape[k] = shape[k];
        tensor->strides[k] = strides[k];
    }
    DLTensor& t = tensor->managed.dl_tensor;
    t.data = const_cast<void*>(data);
    t.device = device < 0 ? DLDevice{kDLCPU, 0} : DLDevice{kDLCUDA, device};
    t.ndim = ndim;
    t.dtype = DLDataType{kDLFloat, static_cast<uint8_t>(8 * realSize), 1};
    t.shape = tensor->shape;
    t.strides = tensor->strides;
    t.byte_offset = 0;
    tensor->managed.manager_ctx = tensor.get();
    tensor->managed.deleter = [](DLManagedTensor* self) { delete static_cast<Tensor*>(self->manager_ctx); };
    return &tensor.release()->managed;
}

}  // namespace structmd::api
