#pragma once
// Marks code that runs both on the host (CPU backend, tests) and on the device (CUDA backend).
// The physics is written once with these markers; no backend-specific copy of a formula exists.
// Kernels compiled at run time (NVRTC: expression potentials) include these same headers without a
// standard library: under __CUDACC_RTC__ the fixed-width integers come from here, and host-only
// code is left out between `#if SMD_HOST_CODE` and `#endif`.
#if defined(__CUDACC_RTC__)
#define SMD_HOST_CODE 0
typedef signed char int8_t;
typedef unsigned char uint8_t;
typedef int int32_t;
typedef unsigned int uint32_t;
typedef long long int64_t;
typedef unsigned long long uint64_t;
#else
#define SMD_HOST_CODE 1
#endif

#if defined(__CUDACC__)
#define SMD_HD __host__ __device__
#define SMD_INLINE __forceinline__
#define SMD_UNROLL4 _Pragma("unroll 4")
#define SMD_UNROLL _Pragma("unroll")
#else
#define SMD_HD
#define SMD_INLINE inline
#define SMD_UNROLL4
#define SMD_UNROLL
#endif

// The CPU backend's own loops (host_rows of the pair kernel and the list build): every call inlined,
// and with g++ on x86-64 a second copy for AVX2 picked at load time where the processor has it
// (twice the vector width of the SSE2 baseline; no FMA, so both copies round alike). Clang refuses
// target_clones beside flatten, and nvcc's host pass never calls these loops.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__CUDACC__)
#define SMD_HOST_LOOP __attribute__((flatten, target_clones("avx2", "default")))
#else
#define SMD_HOST_LOOP __attribute__((flatten))
#endif
