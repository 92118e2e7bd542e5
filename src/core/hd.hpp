#pragma once
// GS_HD marks a function callable from host and device code, so that one
// source of physics serves the CPU backend (plain C++) and the CUDA backend.
#if defined(__CUDACC__)
#define GS_HD __host__ __device__
#define GS_INLINE __forceinline__
#else
#define GS_HD
#define GS_INLINE inline
#endif
