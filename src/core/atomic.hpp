#pragma once
// Atomic integer updates usable from the same functor on both backends.
#include "core/hd.hpp"

namespace structmd {

SMD_HD SMD_INLINE int atomic_add(int* address, int value) {
#if defined(__CUDA_ARCH__)
    return atomicAdd(address, value);
#else
    return __atomic_fetch_add(address, value, __ATOMIC_RELAXED);
#endif
}

SMD_HD SMD_INLINE void atomic_max(int* address, int value) {
#if defined(__CUDA_ARCH__)
    atomicMax(address, value);
#else
    int seen = __atomic_load_n(address, __ATOMIC_RELAXED);
    while (seen < value &&
           !__atomic_compare_exchange_n(address, &seen, value, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
    }
#endif
}

SMD_HD SMD_INLINE void atomic_min(unsigned long long* address, unsigned long long value) {
#if defined(__CUDA_ARCH__)
    atomicMin(address, value);
#else
    unsigned long long seen = __atomic_load_n(address, __ATOMIC_RELAXED);
    while (value < seen &&
           !__atomic_compare_exchange_n(address, &seen, value, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
    }
#endif
}

}  // namespace structmd
