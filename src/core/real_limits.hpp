#pragma once
// The machine epsilon and a quiet NaN of float and double, in host and device code alike. Kernels
// compiled at run time (NVRTC) have no <limits>: there the NaN comes from CUDA's bit casts.
#include "core/hd.hpp"

#if SMD_HOST_CODE
#include <limits>
#endif

namespace structmd {

template <class R>
SMD_HD SMD_INLINE constexpr R machine_epsilon() {
    return sizeof(R) == sizeof(float) ? R(0x1p-23) : R(0x1p-52);
}

template <class R>
SMD_HD SMD_INLINE R quiet_nan() {
#if SMD_HOST_CODE
    return std::numeric_limits<R>::quiet_NaN();
#else
    if constexpr (sizeof(R) == sizeof(float))
        return __int_as_float(0x7fc00000);
    else
        return __longlong_as_double(0x7ff8000000000000LL);
#endif
}

}  // namespace structmd
