#include "rviz_projector/core/polygon_triangulation.h"

#include <algorithm>
#include <cmath>

namespace rviz_projector
{
namespace
{
double cross(const Vec2& a, const Vec2& b) { return a.x * b.y - a.y * b.x; }

double twiceArea(const std::vector<Vec2>& polygon)
{
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    twice += cross(polygon[i], polygon[(i + 1) % polygon.size()]);
  }
  return twice;
}

bool same(const Vec2& a, const Vec2& b) { return a.x == b.x && a.y == b.y; }

/// Segments ab and cd cross at a point inside both (touching at an end does not count).
bool properlyCross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d)
{
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

bool crossesAnyEdge(const Vec2& a, const Vec2& b, const std::vector<Vec2>& ring)
{
  for (std::size_t i = 0; i < ring.size(); ++i)
  {
    if (properlyCross(a, b, ring[i], ring[(i + 1) % ring.size()]))
    {
      return true;
    }
  }
  return false;
}

/// Joins `hole` (clockwise) into `outer` (counter-clockwise) by a bridge from the hole's rightmost
/// vertex to the nearest outer vertex it can see (no edge of the outer ring or the other holes in
/// the way): outer .. P, M, hole round to M, P .. outer.
void bridge(std::vector<Vec2>& outer, std::vector<Vec2> hole, const std::vector<std::vector<Vec2>>& others)
{
  const std::size_t m = std::size_t(std::max_element(hole.begin(), hole.end(),
                                                     [](const Vec2& a, const Vec2& b) { return a.x < b.x; }) -
                                    hole.begin());
  std::rotate(hole.begin(), hole.begin() + std::ptrdiff_t(m), hole.end());
  const Vec2 tip = hole.front();
  std::vector<std::size_t> order(outer.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return distance(outer[a], tip) < distance(outer[b], tip); });
  std::size_t chosen = order.front();
  for (const std::size_t i : order)
  {
    const Vec2& p = outer[i];
    bool clear = !crossesAnyEdge(tip, p, outer) && !crossesAnyEdge(tip, p, hole);
    for (const std::vector<Vec2>& other : others)
    {
      clear = clear && !crossesAnyEdge(tip, p, other);
    }
    if (clear)
    {
      chosen = i;
      break;
    }
  }
  std::vector<Vec2> joined(outer.begin(), outer.begin() + std::ptrdiff_t(chosen) + 1);
  joined.insert(joined.end(), hole.begin(), hole.end());
  joined.push_back(tip);
  joined.push_back(outer[chosen]);
  joined.insert(joined.end(), outer.begin() + std::ptrdiff_t(chosen) + 1, outer.end());
  outer = std::move(joined);
}
}  // namespace

bool insidePolygon(const std::vector<Vec2>& polygon, const Vec2& p)
{
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
  {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x)
    {
      inside = !inside;
    }
  }
  return inside;
}

std::vector<Vec2> triangulatePolygon(std::vector<Vec2> polygon, std::vector<std::vector<Vec2>> holes)
{
  std::vector<Vec2> triangles;
  if (polygon.size() < 3)
  {
    return triangles;
  }
  if (twiceArea(polygon) < 0)
  {
    std::reverse(polygon.begin(), polygon.end());
  }
  // Holes clockwise, rightmost first (each bridge then stays clear of the holes still to come).
  for (std::vector<Vec2>& hole : holes)
  {
    if (twiceArea(hole) > 0)
    {
      std::reverse(hole.begin(), hole.end());
    }
  }
  holes.erase(std::remove_if(holes.begin(), holes.end(), [](const std::vector<Vec2>& h) { return h.size() < 3; }),
              holes.end());
  auto rightmost = [](const std::vector<Vec2>& h) {
    return std::max_element(h.begin(), h.end(), [](const Vec2& a, const Vec2& b) { return a.x < b.x; })->x;
  };
  std::sort(holes.begin(), holes.end(),
            [&](const std::vector<Vec2>& a, const std::vector<Vec2>& b) { return rightmost(a) > rightmost(b); });
  for (std::size_t i = 0; i < holes.size(); ++i)
  {
    const std::vector<std::vector<Vec2>> rest(holes.begin() + std::ptrdiff_t(i) + 1, holes.end());
    bridge(polygon, holes[i], rest);
  }

  // Ear clipping: cut off a convex corner whose triangle holds no other vertex (vertices at the
  // corner's own places, as a bridge repeats them, do not count).
  auto blocks = [](const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
    if (same(p, a) || same(p, b) || same(p, c))
    {
      return false;
    }
    return cross(b - a, p - a) >= 0 && cross(c - b, p - b) >= 0 && cross(a - c, p - c) >= 0;
  };
  std::size_t start = 0;
  while (polygon.size() > 3)
  {
    const std::size_t n = polygon.size();
    bool clipped = false;
    for (std::size_t k = 0; k < n && !clipped; ++k)
    {
      const std::size_t i = (start + k) % n;
      const Vec2& a = polygon[(i + n - 1) % n];
      const Vec2& b = polygon[i];
      const Vec2& c = polygon[(i + 1) % n];
      const double turn = cross(b - a, c - b);
      if (turn < 0)
      {
        continue;  // reflex: not an ear
      }
      if (turn > 0 && std::any_of(polygon.begin(), polygon.end(), [&](const Vec2& p) { return blocks(p, a, b, c); }))
      {
        continue;
      }
      if (turn > 0)
      {
        triangles.insert(triangles.end(), {a, b, c});
      }
      polygon.erase(polygon.begin() + std::ptrdiff_t(i));  // an ear, or a flat corner that adds nothing
      start = i;
      clipped = true;
    }
    if (!clipped)
    {
      break;  // numerically degenerate rest: left out rather than looped on
    }
  }
  if (polygon.size() == 3 && cross(polygon[1] - polygon[0], polygon[2] - polygon[1]) > 0)
  {
    triangles.insert(triangles.end(), polygon.begin(), polygon.end());
  }
  return triangles;
}
double signedArea(const std::vector<Vec2>& polygon)
{
  return 0.5 * twiceArea(polygon);
}
}  // namespace rviz_projector
