#pragma once
#include <cmath>

#include "core/hd.hpp"

namespace gs {

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
template <class T> GS_HD GS_INLINE T dot(const Vec3<T>& a, const Vec3<T>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <class T> GS_HD GS_INLINE Vec3<T> cross(const Vec3<T>& a, const Vec3<T>& b) {
  return Vec3<T>(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
template <class T> GS_HD GS_INLINE T norm2(const Vec3<T>& a) { return dot(a, a); }
template <class T> GS_HD GS_INLINE T norm(const Vec3<T>& a) { return std::sqrt(dot(a, a)); }

}  // namespace gs
