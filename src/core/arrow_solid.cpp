#include "rviz_projector/core/arrow_solid.h"

#include <algorithm>
#include <cmath>

namespace rviz_projector
{
ArrowSolid::ArrowSolid(const Arrow& arrow, const ArrowDimensions& d)
{
  const Vec2 along = arrow.tip - arrow.tail;
  const double length = norm(along);
  if (!std::isfinite(length) || length <= 0.0)
  {
    return;
  }
  valid_ = true;
  shaft_radius_ = 0.5 * std::max(d.shaft_diameter, 0.0);
  head_radius_ = 0.5 * std::max(d.head_diameter, 0.0);
  const double axis_height = std::max(shaft_radius_, head_radius_);
  // The unit direction from hypot: norm() squares the components, which for a vector near the
  // bottom of the double range (1e-162 m) leaves a few bits of precision and a direction 1.6 % off
  // unit length (found by fuzz_shapes); hypot is exact to an ulp there.
  const double exact_length = std::hypot(along.x, along.y);
  forward_ = {along.x / exact_length, along.y / exact_length, 0.0};
  side_ = {-forward_.y, forward_.x, 0.0};
  up_ = {0.0, 0.0, 1.0};
  head_length_ = std::min(std::max(d.head_length, 0.0), length);
  tail_ = {arrow.tail.x, arrow.tail.y, axis_height};
  tip_ = {arrow.tip.x, arrow.tip.y, axis_height};
  neck_ = tip_ - forward_ * head_length_;
}

void ArrowSolid::trianglesOf(const std::vector<Arrow>& arrows, const ArrowDimensions& dimensions,
                             std::vector<MeshVertex>& out, std::size_t limit)
{
  const std::size_t count = std::min(arrows.size(), limit);
  out.clear();
  out.reserve(count * kVerticesPerArrow);
  for (std::size_t i = 0; i < count; ++i)
  {
    ArrowSolid(arrows[i], dimensions).appendTriangles(out);
  }
}

void ArrowSolid::appendTriangles(std::vector<MeshVertex>& out) const
{
  if (!valid_)
  {
    return;
  }
  const double step = 2.0 * M_PI / kSides;
  const Vec3 back = forward_ * -1.0;
  // Cone side normal: the radial direction tilted forward by atan(r / l), as cos and sin of that
  // angle (unit for any r and l: a head 1e-162 m long and 0.3 m wide overflowed r / l as a slope).
  const double tilt = std::atan2(head_radius_, head_length_);
  const double radial = std::cos(tilt), ahead = std::sin(tilt);
  for (int i = 0; i < kSides; ++i)
  {
    const double a0 = step * i;
    const double a1 = step * (i + 1);
    const Vec3 r0 = side_ * std::cos(a0) + up_ * std::sin(a0);
    const Vec3 r1 = side_ * std::cos(a1) + up_ * std::sin(a1);
    // Shaft side (two triangles).
    const Vec3 t0 = tail_ + r0 * shaft_radius_, t1 = tail_ + r1 * shaft_radius_;
    const Vec3 n0 = neck_ + r0 * shaft_radius_, n1 = neck_ + r1 * shaft_radius_;
    out.insert(out.end(), {{t0, r0}, {n1, r1}, {n0, r0}, {t0, r0}, {t1, r1}, {n1, r1}});
    // Tail cap.
    out.insert(out.end(), {{tail_, back}, {t1, back}, {t0, back}});
    // Cone side.
    const Vec3 c0 = neck_ + r0 * head_radius_, c1 = neck_ + r1 * head_radius_;
    const Vec3 m0 = r0 * radial + forward_ * ahead, m1 = r1 * radial + forward_ * ahead;
    Vec3 m_tip = m0 + m1;
    m_tip = m_tip * (1.0 / norm(m_tip));
    out.insert(out.end(), {{c0, m0}, {c1, m1}, {tip_, m_tip}});
    // Cone base, facing back.
    out.insert(out.end(), {{neck_, back}, {c1, back}, {c0, back}});
  }
}
}  // namespace rviz_projector
