#pragma once
// GS_HD marks a function callable from host and device code, so that one
// source of physics serves the CPU backend (plain C++) and the CUDA backend.
#if defined(__CUDACC__)
#define GS_HD __host__ __device__
#define GS_INLINE __forceinline__
#else
#define GS_HD
// Forced, as nvcc's __forceinline__: left to its size limits, GCC keeps the
// contact law's pieces as calls in the CPU force loop, half again slower.
#define GS_INLINE inline __attribute__((always_inline))
#endif
