#pragma once
// The machine epsilon and a quiet NaN of float and double, a rounding to integers, a reciprocal and
// a float from its bits, in host and device code alike. Kernels compiled at run time (NVRTC) have no <limits>: there the NaN comes from
// CUDA's bit casts.
#include "core/hd.hpp"

#if SMD_HOST_CODE
#include <cstring>
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

// x rounded to the nearest integer, ties to even, for |x| below 2^22 (float) or 2^51 (double): adding
// 1.5 times 2 to the mantissa's width leaves no fraction bits, so two additions at the full rate do
// what a conversion (a quarter of the GPU's rate) or a rounding call (a library call on x86-64's
// baseline) would.
template <class R>
SMD_HD SMD_INLINE R nearest_integer(R x) {
    constexpr R kShifter = sizeof(R) == sizeof(float) ? R(12582912.0f) : R(6755399441055744.0);
    return (x + kShifter) - kShifter;
}

// The float whose bits are `bits`.
SMD_HD SMD_INLINE float float_of_bits(int bits) {
#if defined(__CUDA_ARCH__)
    return __int_as_float(bits);
#else
    float x;
    std::memcpy(&x, &bits, sizeof x);
    return x;
#endif
}

// 1 / x. On a GPU in float, the multiprocessor's reciprocal instruction alone (PTX rcp.approx.ftz: within
// 1 ulp, a subnormal x taken as 0), where an IEEE division is some ten instructions and a branch: a
// fifth of a Lennard-Jones pair kernel's instructions a neighbour (sm_90), for an error in 1 / r^2 of
// the order of float's own rounding of the separation. Elsewhere, and in double, the division.
template <class R>
SMD_HD SMD_INLINE R reciprocal(R x) {
#if defined(__CUDA_ARCH__)
    if constexpr (sizeof(R) == sizeof(float)) {
        float y;
        asm("rcp.approx.ftz.f32 %0, %1;" : "=f"(y) : "f"(x));
        return y;
    } else {
        return R(1) / x;
    }
#else
    return R(1) / x;
#endif
}

}  // namespace structmd
