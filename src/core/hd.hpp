#pragma once
// Marks code that runs both on the host (CPU backend, tests) and on the device (CUDA backend).
// The physics is written once with these markers; no backend-specific copy of a formula exists.
#if defined(__CUDACC__)
#define SMD_HD __host__ __device__
#define SMD_INLINE __forceinline__
#define SMD_UNROLL4 _Pragma("unroll 4")
#else
#define SMD_HD
#define SMD_INLINE inline
#define SMD_UNROLL4
#endif
