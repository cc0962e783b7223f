// The engine's arrays as DLPack tensors: shape (n, 3) over records of four reals, so a consumer reads
// x, y, z in place. The tensor owns only its description (shape and strides); the data stay the
// engine's.
#include <dlpack/dlpack.h>

#include <cstdint>
#include <memory>
#include <string>

#include "api/handle.hpp"

using namespace structmd;
using namespace structmd::api;

namespace {

struct ViewTensor {
    DLManagedTensor managed{};
    int64_t shape[2];
    int64_t strides[2] = {4, 1};
};

void delete_view(DLManagedTensor* self) { delete static_cast<ViewTensor*>(self->manager_ctx); }

}  // namespace

extern "C" {

structmd_status structmd_get_view(structmd_sim* sim, const char* quantity, structmd_dlpack_tensor** view) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        require_pointer(quantity, "quantity");
        require_pointer(view, "view");
        const Simulation::ArrayView array = simulation.view(quantity);
        auto tensor = std::make_unique<ViewTensor>();
        tensor->shape[0] = array.n;
        tensor->shape[1] = 3;
        DLTensor& t = tensor->managed.dl_tensor;
        t.data = const_cast<void*>(array.data);
        t.device = array.device < 0 ? DLDevice{kDLCPU, 0} : DLDevice{kDLCUDA, array.device};
        t.ndim = 2;
        t.dtype = DLDataType{kDLFloat, static_cast<uint8_t>(8 * array.realSize), 1};
        t.shape = tensor->shape;
        t.strides = tensor->strides;
        t.byte_offset = 0;
        tensor->managed.manager_ctx = tensor.get();
        tensor->managed.deleter = delete_view;
        *view = &tensor.release()->managed;
    });
}

}  // extern "C"
