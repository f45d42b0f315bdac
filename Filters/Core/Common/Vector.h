// Small fixed-size vector types used by the geometry core (plain structs: no VTK, no Eigen).
#pragma once

#include <algorithm>
#include <cmath>

namespace gs
{

struct Vec2
{
  double x = 0.0, y = 0.0;
  Vec2() = default;
  Vec2(double x_, double y_) : x(x_), y(y_) {}
  Vec2 operator+(const Vec2& o) const { return { x + o.x, y + o.y }; }
  Vec2 operator-(const Vec2& o) const { return { x - o.x, y - o.y }; }
  Vec2 operator*(double s) const { return { x * s, y * s }; }
};

inline double Dot(const Vec2& a, const Vec2& b) { return a.x * b.x + a.y * b.y; }
inline double Cross(const Vec2& a, const Vec2& b) { return a.x * b.y - a.y * b.x; }
inline double Norm(const Vec2& a) { return std::hypot(a.x, a.y); }
/// Norm(a) * scale > bound, decided as that expression decides it, with std::hypot only where
/// the squared length cannot settle it: its rounding (a few units in the last place) is far
/// below the relative margin of 1e-12 kept on either side. Squares that overflow or leave the
/// normal range take std::hypot too. `scale` > 0.
inline bool NormExceeds(const Vec2& a, double bound, double scale = 1.0)
{
  const double dot = Dot(a, a), scale2 = scale * scale;
  const double length2 = dot * scale2, bound2 = bound * bound;
  constexpr double Margin = 1e-12, Tiny = 1e-280, Huge = 1e280;
  auto normal = [](double x) { return x > Tiny && x < Huge; };
  if (bound > 0.0 && normal(dot) && normal(scale2) && normal(length2) && normal(bound2))
  {
    if (length2 > bound2 * (1.0 + Margin))
    {
      return true;
    }
    if (length2 < bound2 * (1.0 - Margin))
    {
      return false;
    }
  }
  return Norm(a) * scale > bound;
}

struct Vec3
{
  double x = 0.0, y = 0.0, z = 0.0;
  Vec3() = default;
  Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
  Vec3 operator+(const Vec3& o) const { return { x + o.x, y + o.y, z + o.z }; }
  Vec3 operator-(const Vec3& o) const { return { x - o.x, y - o.y, z - o.z }; }
  Vec3 operator*(double s) const { return { x * s, y * s, z * s }; }
  Vec3 operator/(double s) const { return { x / s, y / s, z / s }; }
  Vec3& operator+=(const Vec3& o)
  {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};

inline double Dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 Cross(const Vec3& a, const Vec3& b)
{
  return { a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x };
}
inline double Norm(const Vec3& a) { return std::sqrt(Dot(a, a)); }
/// v / |v| (v itself when it is zero).
inline Vec3 Unit(const Vec3& v)
{
  const double l = Norm(v);
  return l > 0.0 ? v / l : v;
}
/// The tangent t turned by `angle` counter-clockwise about the unit normal n (t perpendicular
/// to n): t cos(angle) + (n x t) sin(angle).
inline Vec3 RotateTangent(const Vec3& t, const Vec3& n, double angle)
{
  return t * std::cos(angle) + Cross(n, t) * std::sin(angle);
}
inline bool IsFinite(const Vec3& a)
{
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

// The distance from p to the segment from a to b (a point when a == b).
inline double PointSegmentDistance(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double l2 = Dot(ab, ab);
  double t = l2 > 0.0 ? Dot(p - a, ab) / l2 : 0.0;
  t = std::min(1.0, std::max(0.0, t));
  return Norm(p - (a + ab * t));
}

} // namespace gs
