// libFuzzer target: PathSpacer::space in both modes, parameters and path from the fuzz input
// (NaN/Inf/huge/denormal values included). Invariants: no crash or UB (ASan/UBSan), at most
// max_arrows arrows, NaN/Inf points dropped and counted, the destination is the last finite point,
// finite arrows inside the path's bounding box for sane inputs, Exact arrows no longer than an
// arrow, on the path and in order along it (arc length from the destination grows from tip to
// tail and from one arrow to the next, checked against an arc-length walk of our own), Paper
// arrows join input points in path order, Exact arrows unchanged when the start of the path is
// trimmed, and the same result when the instance is reused.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "fuzz_input.h"
#include "rviz_projector/core/path_spacer.h"

using namespace rviz_projector;
using rviz_projector_fuzz::Input;
using rviz_projector_fuzz::sane;

namespace
{
SpacingParameters parametersFrom(Input& in)
{
  SpacingParameters p;
  // Out-of-range enum values on purpose: setParameters() must fall back to Exact.
  p.mode = static_cast<SpacingMode>(in.integer<int>(-1, 2));
  p.spacing = in.size(2.0);
  p.arrow.shaft_length = in.size(0.5);
  p.arrow.shaft_diameter = in.size(0.5);
  p.arrow.head_length = in.size(0.5);
  p.arrow.head_diameter = in.size(0.5);
  p.circle_diameter = in.size(1.0);
  p.destination_gap = in.size(0.5);
  // The default bound (10^5) now and then: each such input may place 10^5 arrows, twice.
  p.max_arrows = in.integer<std::uint8_t>() < 16 ? SpacingParameters().max_arrows : in.integer<std::size_t>(0, 3000);
  // Speed-coded spacing now and then, with any values (sanitised by speedCodedSpacing): the same
  // invariants hold (on the path, in order, anchored at the destination).
  if (in.integer<std::uint8_t>() < 80)
  {
    p.speed_coding.enabled = true;
    p.speed_coding.speed = in.size(3.0);
    p.speed_coding.deceleration = in.size(2.0);
    p.speed_coding.time_step = in.size(2.0);
    p.speed_coding.min_spacing = in.size(0.5);
  }
  return p;
}

std::vector<Vec2> pathFrom(Input& in)
{
  std::vector<Vec2> path;
  const int kind = in.integer<int>(0, 3);
  if (kind == 0)
  {
    // A long generated polyline (up to 10^4 points): origin, step and curvature from the input.
    const std::size_t n = in.integer<std::size_t>(0, 10000);
    const Vec2 origin = in.vec2(1e9);
    const Vec2 step = in.vec2(1.0);
    const double bend = in.number(0.1);
    path.reserve(n);
    Vec2 p = origin;
    for (std::size_t i = 0; i < n; ++i)
    {
      path.push_back(p);
      const double a = bend * static_cast<double>(i);
      p = p + Vec2{step.x * std::cos(a) - step.y * std::sin(a), step.x * std::sin(a) + step.y * std::cos(a)};
    }
    return path;
  }
  const double range = kind == 1 ? 5.0 : kind == 2 ? 1e9 : 1e-3;
  while (!in.empty() && path.size() < 4000)
  {
    if (!path.empty() && in.integer<std::uint8_t>() < 20)
    {
      path.push_back(path.back());  // repeated poses
    }
    else
    {
      path.push_back(in.vec2(range));
    }
  }
  return path;
}

/**
 * The polyline of the finite points walked from the destination backwards, with the arc length
 * summed here (not by the code under test). locate() finds the smallest arc length >= a lower
 * bound at which a point lies on the polyline (within `tolerance`); the walk only moves forward,
 * so locating a sequence is linear. A greedy smallest choice never rejects a sequence that has an
 * increasing placement, so a failure is a real violation.
 */
class ArcWalk
{
public:
  ArcWalk(const std::vector<Vec2>& points, double tolerance) : points_(points), tolerance_(tolerance)
  {
    from_end_.assign(points.size(), 0.0);
    for (std::size_t i = points.size() - 1; i > 0; --i)
    {
      from_end_[i - 1] = from_end_[i] + distance(points[i], points[i - 1]);
    }
    segment_ = points.size() >= 2 ? points.size() - 2 : 0;
  }

  /// Arc length from the destination of `p` on the polyline, at least `lower` (minus the
  /// tolerance); negative when `p` lies nowhere on the rest of the path.
  double locate(const Vec2& p, double lower)
  {
    const double slack = 4.0 * tolerance_;
    // Segment j runs from points_[j + 1] (arc from_end_[j + 1]) to points_[j] (arc from_end_[j]).
    while (true)
    {
      const Vec2& a = points_[segment_ + 1];
      const Vec2& b = points_[segment_];
      const double start = from_end_[segment_ + 1];
      const double length = from_end_[segment_] - start;
      if (from_end_[segment_] >= lower - slack)
      {
        const Vec2 ab = b - a;
        const double ab2 = dot(ab, ab);
        double t = 0.0;
        if (ab2 > 0.0 && std::isfinite(ab2))
        {
          t = std::min(1.0, std::max(0.0, dot(p - a, ab) / ab2));
        }
        const Vec2 closest = a + ab * t;
        if (distance(p, closest) <= tolerance_)
        {
          const double arc = start + t * length;
          if (arc >= lower - slack)
          {
            return std::max(arc, lower);
          }
          // On this segment, but before the bound: a straight segment holds a point only once.
        }
      }
      if (segment_ == 0)
      {
        return -1.0;
      }
      --segment_;
    }
  }

private:
  const std::vector<Vec2>& points_;
  double tolerance_;
  std::vector<double> from_end_;
  std::size_t segment_;
};

bool sameResult(const SpacedPath& a, const SpacedPath& b)
{
  if (a.arrows.size() != b.arrows.size() || a.has_destination != b.has_destination ||
      a.dropped_points != b.dropped_points || a.truncated != b.truncated)
  {
    return false;
  }
  auto same = [](const Vec2& u, const Vec2& v) {
    return (u.x == v.x || (std::isnan(u.x) && std::isnan(v.x))) && (u.y == v.y || (std::isnan(u.y) && std::isnan(v.y)));
  };
  for (std::size_t i = 0; i < a.arrows.size(); ++i)
  {
    if (!same(a.arrows[i].tip, b.arrows[i].tip) || !same(a.arrows[i].tail, b.arrows[i].tail))
    {
      return false;
    }
  }
  return !a.has_destination || same(a.destination, b.destination);
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  Input in(data, size);
  const SpacingParameters requested = parametersFrom(in);
  const std::vector<Vec2> path = pathFrom(in);

  PathSpacer spacer(requested);
  const SpacingParameters& p = spacer.parameters();
  // Parameters are sanitised: finite, non-negative, spacing at least kMinSpacing, a valid mode.
  RP_FUZZ_CHECK(std::isfinite(p.spacing) && p.spacing >= SpacingParameters::kMinSpacing);
  RP_FUZZ_CHECK(std::isfinite(p.circle_diameter) && p.circle_diameter >= 0.0);
  RP_FUZZ_CHECK(std::isfinite(p.destination_gap) && p.destination_gap >= 0.0);
  RP_FUZZ_CHECK(std::isfinite(p.arrow.shaft_length) && p.arrow.shaft_length >= 0.0);
  RP_FUZZ_CHECK(std::isfinite(p.arrow.shaft_diameter) && p.arrow.shaft_diameter >= 0.0);
  RP_FUZZ_CHECK(std::isfinite(p.arrow.head_length) && p.arrow.head_length >= 0.0);
  RP_FUZZ_CHECK(std::isfinite(p.arrow.head_diameter) && p.arrow.head_diameter >= 0.0);
  RP_FUZZ_CHECK(p.mode == SpacingMode::Exact || p.mode == SpacingMode::Paper);
  RP_FUZZ_CHECK(p.max_arrows == requested.max_arrows);

  const SpacedPath& r = spacer.space(path);

  std::vector<Vec2> finite;
  for (const Vec2& v : path)
  {
    if (isFinite(v))
    {
      finite.push_back(v);
    }
  }
  RP_FUZZ_CHECK(r.arrows.size() <= p.max_arrows);
  RP_FUZZ_CHECK(r.dropped_points == path.size() - finite.size());
  RP_FUZZ_CHECK(r.has_destination == !finite.empty());
  if (finite.empty())
  {
    RP_FUZZ_CHECK(r.arrows.empty());
  }
  else
  {
    RP_FUZZ_CHECK(r.destination.x == finite.back().x && r.destination.y == finite.back().y);
  }
  RP_FUZZ_CHECK(!std::isnan(r.path_length) && r.path_length >= 0.0);
  if (finite.size() < 2)
  {
    RP_FUZZ_CHECK(r.arrows.empty() || p.mode == SpacingMode::Paper);
  }

  const bool all_sane = std::all_of(finite.begin(), finite.end(), [](const Vec2& v) { return sane(v); });
  if (all_sane && !finite.empty())
  {
    RP_FUZZ_CHECK(std::isfinite(r.path_length));
    Vec2 lo = finite.front(), hi = finite.front();
    for (const Vec2& v : finite)
    {
      lo = Vec2{std::min(lo.x, v.x), std::min(lo.y, v.y)};
      hi = Vec2{std::max(hi.x, v.x), std::max(hi.y, v.y)};
    }
    const double extent = std::max({1.0, std::fabs(lo.x), std::fabs(lo.y), std::fabs(hi.x), std::fabs(hi.y)});
    const double tol = 1e-9 * extent;
    auto inside = [&](const Vec2& v) {
      return v.x >= lo.x - tol && v.x <= hi.x + tol && v.y >= lo.y - tol && v.y <= hi.y + tol;
    };
    std::vector<std::pair<double, double>> sorted;
    if (p.mode == SpacingMode::Paper)
    {
      for (const Vec2& v : finite)
      {
        sorted.emplace_back(v.x, v.y);
      }
      std::sort(sorted.begin(), sorted.end());
    }
    auto isInputPoint = [&](const Vec2& v) {
      return std::binary_search(sorted.begin(), sorted.end(), std::make_pair(v.x, v.y));
    };
    for (const Arrow& a : r.arrows)
    {
      RP_FUZZ_CHECK(isFinite(a.tip) && isFinite(a.tail));
      RP_FUZZ_CHECK(inside(a.tip) && inside(a.tail));
      if (p.mode == SpacingMode::Exact)
      {
        // The chord tail -> tip is never longer than the arc it spans (one arrow length).
        RP_FUZZ_CHECK(distance(a.tip, a.tail) <= p.arrow.length() * (1.0 + 1e-9) + 4.0 * tol);
      }
      else
      {
        RP_FUZZ_CHECK(isInputPoint(a.tip) && isInputPoint(a.tail));
      }
    }
    if (p.mode == SpacingMode::Paper && !r.arrows.empty())
    {
      RP_FUZZ_CHECK(r.arrows.front().tip.x == r.destination.x && r.arrows.front().tip.y == r.destination.y);
      // In path order: tip 0, tail 0, tip 1, tail 1, ... are input points at strictly decreasing
      // indices (the walk goes from the destination towards the start).
      std::size_t next = finite.size();  // the next point must have an index below this
      auto at = [&](const Vec2& v) {
        while (next > 0)
        {
          --next;
          if (finite[next].x == v.x && finite[next].y == v.y)
          {
            return true;
          }
        }
        return false;
      };
      for (const Arrow& a : r.arrows)
      {
        RP_FUZZ_CHECK(at(a.tip) && "Paper: arrows out of path order");
        RP_FUZZ_CHECK(at(a.tail) && "Paper: arrows out of path order");
      }
    }
    if (p.mode == SpacingMode::Exact && !r.arrows.empty())
    {
      // On the path and in order: tips at growing arc length from the destination, tails too,
      // each tail at or beyond its own tip. Tolerance: rounding of the coordinates' magnitude and
      // of the arc length summed over the path.
      const double tolerance = 1e-9 * (extent + r.path_length);
      ArcWalk tips(finite, tolerance);
      ArcWalk tails(finite, tolerance);
      double tip_arc = 0.0;
      double tail_arc = 0.0;
      for (const Arrow& a : r.arrows)
      {
        tip_arc = tips.locate(a.tip, tip_arc);
        RP_FUZZ_CHECK(tip_arc >= 0.0 && "Exact: a tip is off the path or out of order");
        tail_arc = tails.locate(a.tail, std::max(tail_arc, tip_arc));
        RP_FUZZ_CHECK(tail_arc >= 0.0 && "Exact: a tail is off the path, before its tip, or out of order");
      }
    }
  }

  // Exact mode is anchored at the destination: trimming the start of the path (the robot driving
  // along its plan) leaves every remaining arrow bit-for-bit where it was (path_spacer.h).
  if (p.mode == SpacingMode::Exact && all_sane && r.dropped_points == 0 && path.size() >= 3 && !r.truncated)
  {
    const SpacedPath full = r;
    const std::vector<Vec2> trimmed(path.begin() + 1, path.end());
    PathSpacer other(requested);
    const SpacedPath& t = other.space(trimmed);
    RP_FUZZ_CHECK(t.arrows.size() <= full.arrows.size());
    for (std::size_t k = 0; k < t.arrows.size(); ++k)
    {
      RP_FUZZ_CHECK(t.arrows[k].tip.x == full.arrows[k].tip.x && t.arrows[k].tip.y == full.arrows[k].tip.y);
      RP_FUZZ_CHECK(t.arrows[k].tail.x == full.arrows[k].tail.x && t.arrows[k].tail.y == full.arrows[k].tail.y);
    }
  }

  // Reusing the instance (its buffers) gives the same result as a fresh one.
  const SpacedPath first = r;
  const SpacedPath& again = spacer.space(path);
  RP_FUZZ_CHECK(sameResult(first, again));
  return 0;
}
