#pragma once
// The host's force terms (structmd_set_force_callback, structmd_set_device_force_callback) as the
// engine sees them: functions that add forces, an energy and a virial for the present positions and
// throw an Error on failure. The API layer wraps the C callbacks into these, so the engine knows
// nothing of C function pointers, user data or the host's error message.
#include <cstdint>
#include <functional>

namespace structmd {

// Host memory, id order, 3 doubles per particle; forces, energy and virial are zero on entry.
struct HostForceCall {
    const double* positions;
    double* forces;
    int64_t n;
    double* energy;
    double* virial;  // 9, row-major
    int64_t step;
};
using HostForceCallback = std::function<void(const HostForceCall&)>;

// The backend's own Real4 arrays (device memory on CUDA) and the stream their work runs on.
struct DeviceForceCall {
    const void* positions;
    void* forces;
    int64_t n;
    int realSize;  // bytes of one real
    double* energy;
    double* virial;
    int64_t step;
    void* stream;  // null on the CPU backend
};
using DeviceForceCallback = std::function<void(const DeviceForceCall&)>;

}  // namespace structmd
