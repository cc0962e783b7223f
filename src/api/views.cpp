// The engine's arrays as DLPack tensors: shape (n, 3) over records of four reals, so a consumer reads
// x, y, z in place.
#include "api/dlpack_tensor.hpp"
#include "api/handle.hpp"

using namespace structmd;
using namespace structmd::api;

extern "C" {

structmd_status structmd_get_view(structmd_sim* sim, const char* quantity, structmd_dlpack_tensor** view) {
    return with_handle(sim, [&](structmd_sim& s) {
        Simulation& simulation = loaded(s);
        require_pointer(quantity, "quantity");
        require_pointer(view, "view");
        const Simulation::ArrayView array = simulation.view(quantity);
        const int64_t shape[2] = {array.n, 3};
        const int64_t strides[2] = {4, 1};
        *view = make_engine_tensor(array.data, array.device, array.realSize, 2, shape, strides);
    });
}

}  // extern "C"
