#pragma once
// The step counter and simulation time, kept on the backend beside the particles and advanced by
// a kernel at the end of every step. Kernels that need the step (the counter of the thermal
// noise, the step named in a fault report) or the time (fields that move) read it there, so their
// arguments are the same at every step and a recorded sequence of steps can be replayed as is.
// Free of the standard library: kernels compiled at run time (core/hd.hpp) read the clock too.
#include "core/hd.hpp"

#if SMD_HOST_CODE
#include <cstdint>
#endif

namespace structmd {

struct StepClock {
    int64_t step = 0;
    double time = 0.0;
};

// The step and time being computed, as the clock on the backend plus offsets known to the host
// when the kernel is launched (a kernel launched after the drift sees the next step's values).
struct ClockView {
    const StepClock* clock = nullptr;
    int64_t stepOffset = 0;
    double timeOffset = 0.0;

    SMD_HD SMD_INLINE int64_t step() const { return clock->step + stepOffset; }
    SMD_HD SMD_INLINE double time() const { return clock->time + timeOffset; }
};

struct AdvanceClock {
    StepClock* clock;
    double elapsed;
    SMD_HD void operator()(int64_t) const {
        clock->step += 1;
        clock->time += elapsed;
    }
};

}  // namespace structmd
