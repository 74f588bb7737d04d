#include "rviz_projector/core/stop_zone.h"

#include <algorithm>
#include <cmath>

#include "rviz_projector/core/path_location.h"

namespace rviz_projector
{
double stoppingDistance(double speed, double deceleration, double reaction_time)
{
  if (!std::isfinite(speed) || !std::isfinite(deceleration) || !std::isfinite(reaction_time) ||
      !(deceleration > 0.0) || reaction_time < 0.0)
  {
    return std::nan("");
  }
  const double v = std::abs(speed);
  return v * v / (2.0 * deceleration) + v * reaction_time;
}

void SpeedFilter::add(double speed, double time)
{
  if (!std::isfinite(speed) || !std::isfinite(time))
  {
    return;
  }
  const double v = std::abs(speed);
  if (!has_value_ || time < time_)
  {
    has_value_ = true;
    value_ = v;  // the first measurement as it is
    moving_ = v > kMoveAbove;
  }
  else
  {
    value_ = valueAt(time);
  }
  input_ = v;
  time_ = time;
}

double SpeedFilter::valueAt(double time) const
{
  const double dt = time - time_;
  if (!(dt > 0.0))
  {
    return value_;
  }
  return input_ + (value_ - input_) * std::exp(-dt / kTimeConstant);
}

SpeedEstimate SpeedFilter::at(double time)
{
  SpeedEstimate estimate;
  if (!has_value_)
  {
    moving_ = false;
    return estimate;
  }
  estimate.speed = valueAt(time);
  if (moving_ && estimate.speed < kStandBelow)
  {
    moving_ = false;
  }
  else if (!moving_ && estimate.speed > kMoveAbove)
  {
    moving_ = true;
  }
  estimate.moving = moving_;
  return estimate;
}

void SpeedFilter::clear()
{
  *this = SpeedFilter();
}

namespace
{
/// Unit left normal of the segment a -> b (zero for a zero-length segment).
Vec2 leftNormal(const Vec2& a, const Vec2& b)
{
  const Vec2 d = b - a;
  const double n = norm(d);
  return n > 0.0 ? perpendicular(d) * (1.0 / n) : Vec2{};
}
}  // namespace

void appendPathBand(const std::vector<Vec2>& points, const std::vector<double>& lengths, double from, double to,
                    double width, std::vector<Vec2>& out)
{
  PathBandScratch scratch;
  appendPathBand(points, lengths, from, to, width, out, scratch);
}

void appendPathBand(const std::vector<Vec2>& points, const std::vector<double>& lengths, double from, double to,
                    double width, std::vector<Vec2>& out, PathBandScratch& scratch)
{
  if (points.size() < 2 || lengths.size() != points.size() || !std::isfinite(from) || !std::isfinite(to) ||
      !(width > 0.0))
  {
    return;
  }
  const double total = lengths.back();
  from = std::clamp(from, 0.0, total);
  to = std::clamp(to, 0.0, total);
  if (!(to > from))
  {
    return;
  }
  // The centre line: the strip's ends and the path points between them (repeated points dropped).
  std::vector<Vec2>& centre = scratch.centre;
  centre.clear();
  centre.push_back(pointAtArcLength(points, lengths, from));
  const auto first = std::upper_bound(lengths.begin(), lengths.end(), from);
  for (std::size_t i = static_cast<std::size_t>(first - lengths.begin()); i < points.size() && lengths[i] < to; ++i)
  {
    if (distance(points[i], centre.back()) > 1e-9)
    {
      centre.push_back(points[i]);
    }
  }
  const Vec2 last = pointAtArcLength(points, lengths, to);
  if (distance(last, centre.back()) > 1e-9)
  {
    centre.push_back(last);
  }
  if (centre.size() < 2)
  {
    return;
  }
  const double half = 0.5 * width;
  std::vector<Vec2>& offset = scratch.offset;
  offset.resize(centre.size());
  for (std::size_t i = 0; i < centre.size(); ++i)
  {
    const Vec2 before = i > 0 ? leftNormal(centre[i - 1], centre[i]) : leftNormal(centre[0], centre[1]);
    const Vec2 after = i + 1 < centre.size() ? leftNormal(centre[i], centre[i + 1]) : before;
    const Vec2 sum = before + after;
    const double n = norm(sum);
    if (!(n > 1e-9))
    {
      offset[i] = before * half;  // the path turns back on itself
      continue;
    }
    const Vec2 bisector = sum * (1.0 / n);
    // Mitre: the edges stay `half` away from both segments; at most 2 * half on very sharp corners.
    const double cosine = std::max(0.5, dot(bisector, before));
    offset[i] = bisector * (half / cosine);
  }
  for (std::size_t i = 0; i + 1 < centre.size(); ++i)
  {
    const Vec2 l0 = centre[i] + offset[i], r0 = centre[i] - offset[i];
    const Vec2 l1 = centre[i + 1] + offset[i + 1], r1 = centre[i + 1] - offset[i + 1];
    out.insert(out.end(), {r0, r1, l1, r0, l1, l0});
  }
}

void StopZone::build(const std::vector<Vec2>& points, const std::vector<double>& lengths, double robot_arc,
                     const SpeedEstimate& speed, const StopZoneParameters& parameters)
{
  triangles_.clear();
  alpha_.clear();
  start_ = end_ = 0.0;
  const double d = stoppingDistance(speed.speed, parameters.deceleration, parameters.reaction_time);
  if (!speed.moving || !std::isfinite(d) || !std::isfinite(robot_arc) || points.size() < 2 ||
      lengths.size() != points.size())
  {
    return;
  }
  const double total = lengths.back();
  const double start = std::clamp(robot_arc, 0.0, total);
  const double end = std::min(start + d, total);  // never beyond the destination
  if (!(end - start >= 1e-3))
  {
    return;
  }
  const double bar_start = std::max(start, end - kStopBarThickness);
  const auto fill = [&](double from, double to) {
    appendPathBand(points, lengths, from, to, parameters.width, triangles_, scratch_);
  };
  if (parameters.hatched)
  {
    // At most kStopMaxStripes (300 m): beyond that the rest is filled (bogus odometry speeds must
    // not cost a frame millions of stripes).
    double s = start;
    for (int k = 0; k < kStopMaxStripes && s < bar_start; ++k, s = start + k * kStopStripePeriod)
    {
      fill(s, std::min(s + kStopStripeLength, bar_start));
    }
    fill(s, bar_start);
  }
  else
  {
    fill(start, bar_start);
  }
  alpha_.assign(triangles_.size(), static_cast<float>(std::clamp(parameters.fill_alpha, 0.0, 1.0)));
  appendPathBand(points, lengths, bar_start, end, parameters.width, triangles_, scratch_);
  alpha_.resize(triangles_.size(), 1.0f);
  start_ = start;
  end_ = end;
}
}  // namespace rviz_projector
