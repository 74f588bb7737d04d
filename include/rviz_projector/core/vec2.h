// Planar vector in metres (x, y of the floor plane). Plain value type, no ROS/OGRE.
#pragma once

#include <cmath>

namespace rviz_projector
{
struct Vec2
{
  double x = 0.0;
  double y = 0.0;
};

inline Vec2 operator+(const Vec2& a, const Vec2& b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(const Vec2& a, const Vec2& b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(const Vec2& a, double s) { return {a.x * s, a.y * s}; }
inline double dot(const Vec2& a, const Vec2& b) { return a.x * b.x + a.y * b.y; }
/// sqrt, not std::hypot: several times faster, and floor coordinates never come near overflow.
inline double norm(const Vec2& a) { return std::sqrt(a.x * a.x + a.y * a.y); }
inline double distance(const Vec2& a, const Vec2& b) { return norm(a - b); }
inline bool isFinite(const Vec2& a) { return std::isfinite(a.x) && std::isfinite(a.y); }
/// Left-hand perpendicular (rotated +90 degrees).
inline Vec2 perpendicular(const Vec2& a) { return {-a.y, a.x}; }
}  // namespace rviz_projector
