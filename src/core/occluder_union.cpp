#include "rviz_projector/core/occluder_union.h"

#include <clipper.hpp>

#include <algorithm>
#include <cmath>

#include "rviz_projector/core/polygon_triangulation.h"

namespace rviz_projector
{
namespace
{
// Clipper works on integers: 0.1 mm, relative to the first square's centre.
constexpr double kScale = 1e4;

ClipperLib::cInt toUnits(double metres)
{
  return ClipperLib::cInt(std::llround(metres * kScale));
}

/// A ring in metres, counter-clockwise when `ccw`, else clockwise.
std::vector<Vec2> ring(ClipperLib::Path path, const Vec2& origin, bool ccw)
{
  if (ClipperLib::Orientation(path) != ccw)
  {
    ClipperLib::ReversePath(path);
  }
  std::vector<Vec2> out;
  out.reserve(path.size());
  for (const ClipperLib::IntPoint& p : path)
  {
    out.push_back({origin.x + double(p.X) / kScale, origin.y + double(p.Y) / kScale});
  }
  return out;
}
}  // namespace

bool OccluderUnion::build(const std::vector<OccluderSquares>& sets, double height)
{
  triangles_.clear();
  squares_ = 0;
  if (!(std::isfinite(height) && height > 0.0))
  {
    return true;
  }
  ClipperLib::Paths squares;
  bool have_origin = false;
  Vec2 origin{0.0, 0.0};
  for (const OccluderSquares& set : sets)
  {
    if (set.points == nullptr || !(std::isfinite(set.margin) && set.margin > 0.0 && set.margin < kMaxExtent))
    {
      continue;
    }
    for (const Vec2& p : *set.points)
    {
      if (!isFinite(p))
      {
        continue;
      }
      if (!have_origin)
      {
        origin = p;
        have_origin = true;
      }
      const Vec2 c{p.x - origin.x, p.y - origin.y};
      if (!(std::abs(c.x) <= kMaxExtent && std::abs(c.y) <= kMaxExtent) || squares.size() >= kMaxSquares)
      {
        return false;
      }
      const ClipperLib::cInt x0 = toUnits(c.x - set.margin), x1 = toUnits(c.x + set.margin);
      const ClipperLib::cInt y0 = toUnits(c.y - set.margin), y1 = toUnits(c.y + set.margin);
      squares.push_back({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
    }
  }
  if (squares.empty())
  {
    return true;
  }
  ClipperLib::PolyTree tree;
  try
  {
    ClipperLib::Clipper clipper;
    clipper.AddPaths(squares, ClipperLib::ptSubject, true);
    if (!clipper.Execute(ClipperLib::ctUnion, tree, ClipperLib::pftNonZero, ClipperLib::pftNonZero))
    {
      return false;
    }
  }
  catch (const ClipperLib::clipperException&)  // coordinates out of its range: not with kMaxExtent
  {
    return false;
  }
  const double h = height;
  const auto wall = [this, h](const std::vector<Vec2>& r) {
    // Solid on the left of every edge (outer rings counter-clockwise, holes clockwise): the
    // outward normal is on the right. a b b' a' counter-clockwise seen from outside.
    for (std::size_t i = 0; i < r.size(); ++i)
    {
      const Vec2& a = r[i];
      const Vec2& b = r[(i + 1) % r.size()];
      const double dx = b.x - a.x, dy = b.y - a.y, length = std::hypot(dx, dy);
      if (!(length > 0.0))
      {
        continue;
      }
      const Vec3 n{dy / length, -dx / length, 0.0};
      const Vec3 a0{a.x, a.y, 0.0}, b0{b.x, b.y, 0.0}, b1{b.x, b.y, h}, a1{a.x, a.y, h};
      triangles_.insert(triangles_.end(),
                        {MeshVertex{a0, n}, MeshVertex{b0, n}, MeshVertex{b1, n}, MeshVertex{a0, n}, MeshVertex{b1, n},
                         MeshVertex{a1, n}});
    }
  };
  // Outer rings with their holes; islands inside a hole are outer rings again (the tree's depth).
  std::vector<const ClipperLib::PolyNode*> outers;
  for (const ClipperLib::PolyNode* node = tree.GetFirst(); node != nullptr; node = node->GetNext())
  {
    if (!node->IsHole())
    {
      outers.push_back(node);
    }
  }
  for (const ClipperLib::PolyNode* node : outers)
  {
    const std::vector<Vec2> outer = ring(node->Contour, origin, true);
    std::vector<std::vector<Vec2>> holes;
    double expected = signedArea(outer);
    for (const ClipperLib::PolyNode* child : node->Childs)
    {
      holes.push_back(ring(child->Contour, origin, false));
      expected += signedArea(holes.back());  // negative: clockwise
    }
    wall(outer);
    for (const std::vector<Vec2>& hole : holes)
    {
      wall(hole);
    }
    const std::vector<Vec2> top = triangulatePolygon(outer, holes);
    double covered = 0.0;
    for (std::size_t i = 0; i + 2 < top.size(); i += 3)
    {
      covered += signedArea({top[i], top[i + 1], top[i + 2]});
      const Vec3 up{0.0, 0.0, 1.0};
      triangles_.insert(triangles_.end(), {MeshVertex{{top[i].x, top[i].y, h}, up},
                                           MeshVertex{{top[i + 1].x, top[i + 1].y, h}, up},
                                           MeshVertex{{top[i + 2].x, top[i + 2].y, h}, up}});
    }
    // The top must cover the outline exactly (a gap would show the floor inside from above).
    if (!(std::abs(covered - expected) <= 1e-9 * std::max(1.0, std::abs(expected)) + 1e-12))
    {
      triangles_.clear();
      return false;
    }
  }
  squares_ = squares.size();  // only for a union formed
  return true;
}
}  // namespace rviz_projector
