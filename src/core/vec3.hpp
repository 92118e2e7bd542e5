#pragma once
#include <cmath>

#include "core/hd.hpp"

namespace gs {

// a * b + c, fused (one rounding) where the target has fused multiply-add:
// GPUs, and x86-64-v3 host code (cmake/cpu_arch.cmake); two roundings
// elsewhere. The host compiler is not allowed to fuse on its own
// (-ffp-contract=off): it fuses an expression or not depending on the code
// inlined around it, and the same contact, computed in two kernels (a rank
// with and without neighbours), would round differently.
GS_HD GS_INLINE float mul_add(float a, float b, float c) {
#if defined(__CUDA_ARCH__)
  return fmaf(a, b, c);
#elif defined(__FMA__)
  return __builtin_fmaf(a, b, c);  // not std::fma: GCC would count it as a call and stop inlining around it
#else
  return a * b + c;
#endif
}
GS_HD GS_INLINE double mul_add(double a, double b, double c) {
#if defined(__CUDA_ARCH__)
  return fma(a, b, c);
#elif defined(__FMA__)
  return __builtin_fma(a, b, c);
#else
  return a * b + c;
#endif
}

// a + b rounded on its own, never fused with a product that feeds it (nvcc
// fuses where the source does not forbid it). A particle's force sum adds
// with it, so that the sum has the same bits whether the thread computed each
// contact itself or received it from another lane of its group
// (engine/force_kernel.hpp, in_group). The host never fuses on its own.
GS_HD GS_INLINE float add_rounded(float a, float b) {
#if defined(__CUDA_ARCH__)
  return __fadd_rn(a, b);
#else
  return a + b;
#endif
}
GS_HD GS_INLINE double add_rounded(double a, double b) {
#if defined(__CUDA_ARCH__)
  return __dadd_rn(a, b);
#else
  return a + b;
#endif
}

// A small 3-vector usable in host and device code. T is float or double.
template <class T>
struct Vec3 {
  T x, y, z;

  GS_HD Vec3() : x(0), y(0), z(0) {}
  GS_HD Vec3(T x_, T y_, T z_) : x(x_), y(y_), z(z_) {}
  template <class U>
  GS_HD explicit Vec3(const Vec3<U>& o) : x(T(o.x)), y(T(o.y)), z(T(o.z)) {}

  GS_HD Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
  GS_HD Vec3& operator-=(const Vec3& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
  GS_HD Vec3& operator*=(T s) { x *= s; y *= s; z *= s; return *this; }
};

using Vec3d = Vec3<double>;
using Vec3f = Vec3<float>;

template <class T> GS_HD GS_INLINE Vec3<T> operator+(Vec3<T> a, const Vec3<T>& b) { return a += b; }
template <class T> GS_HD GS_INLINE Vec3<T> operator-(Vec3<T> a, const Vec3<T>& b) { return a -= b; }
template <class T> GS_HD GS_INLINE Vec3<T> operator-(const Vec3<T>& a) { return Vec3<T>(-a.x, -a.y, -a.z); }
template <class T> GS_HD GS_INLINE Vec3<T> operator*(Vec3<T> a, T s) { return a *= s; }
template <class T> GS_HD GS_INLINE Vec3<T> operator*(T s, Vec3<T> a) { return a *= s; }
template <class T> GS_HD GS_INLINE T dot(const Vec3<T>& a, const Vec3<T>& b) {
  return mul_add(a.x, b.x, mul_add(a.y, b.y, a.z * b.z));
}
template <class T> GS_HD GS_INLINE Vec3<T> cross(const Vec3<T>& a, const Vec3<T>& b) {
  return Vec3<T>(mul_add(a.y, b.z, -(a.z * b.y)), mul_add(a.z, b.x, -(a.x * b.z)), mul_add(a.x, b.y, -(a.y * b.x)));
}
// a * s + c, component by component.
template <class T> GS_HD GS_INLINE Vec3<T> mul_add(const Vec3<T>& a, T s, const Vec3<T>& c) {
  return Vec3<T>(mul_add(a.x, s, c.x), mul_add(a.y, s, c.y), mul_add(a.z, s, c.z));
}
template <class T> GS_HD GS_INLINE Vec3<T> add_rounded(const Vec3<T>& a, const Vec3<T>& b) {
  return Vec3<T>(add_rounded(a.x, b.x), add_rounded(a.y, b.y), add_rounded(a.z, b.z));
}
template <class T> GS_HD GS_INLINE T norm2(const Vec3<T>& a) { return dot(a, a); }
template <class T> GS_HD GS_INLINE T norm(const Vec3<T>& a) { return std::sqrt(dot(a, a)); }

}  // namespace gs
