#include "rviz_projector/core/path_spacer.h"

#include "rviz_projector/core/arrow_outline.h"

#include <algorithm>
#include <iterator>
#include <cmath>

namespace rviz_projector
{
namespace
{
double finiteAtLeast(double value, double minimum, double fallback)
{
  if (!std::isfinite(value))
  {
    return fallback;
  }
  return std::max(value, minimum);
}

/**
 * Walks a polyline from its last point towards its first and returns the point at a given arc
 * length from the last point. Arc lengths asked for must not decrease between calls, which keeps
 * the whole walk linear. It reads the arc lengths accumulated from the last point (`from_end`), so
 * the same tail of a path always yields bit-identical points.
 */
class BackwardWalker
{
public:
  BackwardWalker(const std::vector<Vec2>& points, const std::vector<double>& from_end)
    : points_(points), from_end_(from_end), segment_(points.size() >= 2 ? points.size() - 2 : 0)
  {
  }

  Vec2 pointAt(double arc_length)
  {
    // Segment j runs from points_[j + 1] (from_end_[j + 1] from the end) to points_[j].
    while (segment_ > 0 && arc_length > from_end_[segment_])
    {
      --segment_;
    }
    const Vec2& near_end = points_[segment_ + 1];
    const double start = from_end_[segment_ + 1];
    const double length = from_end_[segment_] - start;
    if (length <= 0.0)
    {
      return near_end;
    }
    const double fraction = std::min(1.0, std::max(0.0, (arc_length - start) / length));
    return near_end + (points_[segment_] - near_end) * fraction;
  }

private:
  const std::vector<Vec2>& points_;
  const std::vector<double>& from_end_;
  std::size_t segment_;
};
}  // namespace

PathSpacer::PathSpacer(const SpacingParameters& parameters)
{
  setParameters(parameters);
}

void PathSpacer::setParameters(const SpacingParameters& parameters)
{
  const SpacingParameters defaults;
  parameters_ = parameters;
  parameters_.spacing = finiteAtLeast(parameters.spacing, SpacingParameters::kMinSpacing, defaults.spacing);
  parameters_.circle_diameter = finiteAtLeast(parameters.circle_diameter, 0.0, defaults.circle_diameter);
  parameters_.destination_gap = finiteAtLeast(parameters.destination_gap, 0.0, defaults.destination_gap);
  ArrowDimensions& arrow = parameters_.arrow;
  arrow.shaft_length = finiteAtLeast(arrow.shaft_length, 0.0, defaults.arrow.shaft_length);
  arrow.shaft_diameter = finiteAtLeast(arrow.shaft_diameter, 0.0, defaults.arrow.shaft_diameter);
  arrow.head_length = finiteAtLeast(arrow.head_length, 0.0, defaults.arrow.head_length);
  arrow.head_diameter = finiteAtLeast(arrow.head_diameter, 0.0, defaults.arrow.head_diameter);
  if (parameters_.mode != SpacingMode::Exact && parameters_.mode != SpacingMode::Paper)
  {
    parameters_.mode = SpacingMode::Exact;
  }
}

const SpacedPath& PathSpacer::space(const std::vector<Vec2>& path, double phase)
{
  phase_ = std::isfinite(phase) ? std::fmod(phase, parameters_.spacing) : 0.0;
  if (phase_ < 0.0)
  {
    phase_ += parameters_.spacing;
  }
  if (!(phase_ < parameters_.spacing))
  {
    phase_ = 0.0;  // fmod rounding up to the spacing itself
  }
  result_.arrows.clear();
  result_.tip_from_end.clear();
  result_.has_destination = false;
  result_.destination = Vec2();
  result_.truncated = false;
  result_.path_length = 0.0;

  // Usually every point is finite: then the input is used as it is, without a copy, and one pass
  // accumulates the arc length from the destination back to each point (from the destination, so
  // a trimmed start leaves the rest bit-identical). A non-finite sum sends the path through the
  // filter below and a second pass over the finite points only.
  points_in_use_ = &path;
  result_.dropped_points = 0;
  if (path.empty())
  {
    return result_;
  }
  accumulateFromEnd(path);
  if ((!std::isfinite(from_end_.front()) || !isFinite(path.back())) &&  // (back: a one-point path)
      !std::all_of(path.begin(), path.end(), [](const Vec2& p) { return isFinite(p); }))
  {
    points_.clear();
    points_.reserve(path.size());
    std::copy_if(path.begin(), path.end(), std::back_inserter(points_), [](const Vec2& p) { return isFinite(p); });
    result_.dropped_points = path.size() - points_.size();
    points_in_use_ = &points_;
    if (points_.empty())
    {
      return result_;
    }
    accumulateFromEnd(points_);
  }
  const std::vector<Vec2>& points = *points_in_use_;
  result_.has_destination = true;
  result_.destination = points.back();
  result_.path_length = from_end_.front();

  if (parameters_.mode == SpacingMode::Paper)
  {
    placePaper();
  }
  else
  {
    placeExact();
  }
  return result_;
}

void PathSpacer::accumulateFromEnd(const std::vector<Vec2>& points)
{
  from_end_.resize(points.size());
  double sum = 0.0;
  from_end_.back() = sum;
  for (std::size_t i = points.size() - 1; i > 0; --i)
  {
    sum += distance(points[i], points[i - 1]);
    from_end_[i - 1] = sum;
  }
}

void PathSpacer::placeExact()
{
  const double radius = 0.5 * parameters_.circle_diameter;
  const bool speed_coded = parameters_.speed_coding.enabled;
  const double first_tip = radius + parameters_.destination_gap + (speed_coded ? 0.0 : phase_);
  const double arrow_length = parameters_.arrow.length();
  const double total = result_.path_length;
  const std::vector<Vec2>& points = *points_in_use_;
  if (points.size() < 2 || first_tip + arrow_length > total)
  {
    return;
  }
  // Count first so the vector is sized once; the count is bounded by max_arrows. Speed-coded tips
  // are listed first (their spacing varies), the others follow from the constant spacing.
  std::size_t count = parameters_.max_arrows;
  if (speed_coded)
  {
    result_.tip_from_end.clear();
    for (double tip_s = first_tip; tip_s + arrow_length <= total;
         tip_s += speedCodedSpacing(parameters_.speed_coding, tip_s))
    {
      if (result_.tip_from_end.size() == parameters_.max_arrows)
      {
        result_.truncated = true;
        break;
      }
      result_.tip_from_end.push_back(tip_s);
    }
    count = result_.tip_from_end.size();
  }
  else
  {
    const double fitting = std::floor((total - first_tip - arrow_length) / parameters_.spacing) + 1.0;
    if (fitting < static_cast<double>(parameters_.max_arrows))
    {
      count = static_cast<std::size_t>(fitting);
    }
    else
    {
      result_.truncated = fitting > static_cast<double>(parameters_.max_arrows);
    }
    result_.tip_from_end.resize(count);
  }
  result_.arrows.resize(count);

  // Tips and tails each have their own walker: both sequences grow, but a tail may lie beyond the
  // next tip (arrow longer than the spacing), so one shared walker could not stay monotonic.
  const double half_width = 0.5 * std::max(parameters_.arrow.shaft_diameter, parameters_.arrow.head_diameter);
  const double clear_of_circle = (radius + arrow_length + half_width) * (1.0 + 1e-9) + 1e-9;
  BackwardWalker tips(points, from_end_);
  BackwardWalker tails(points, from_end_);
  std::size_t placed = 0;
  for (std::size_t k = 0; k < count; ++k)
  {
    const double tip_s = speed_coded ? result_.tip_from_end[k] : first_tip + static_cast<double>(k) * parameters_.spacing;
    const double tail_s = tip_s + arrow_length;
    if (tail_s > total)
    {
      break;  // rounding in `fitting`; never draw an arrow that leaves the path
    }
    Arrow& arrow = result_.arrows[placed];
    arrow.tip = tips.pointAt(tip_s);
    arrow.tail = tails.pointAt(tail_s);
    // A path curling back round its goal can bring an arrow over the circle: leave that one out.
    // The outline lies within half its widest diameter of the segment tail-tip, which is no longer
    // than the arc between them, so an arrow whose tip is further than that from the circle cannot
    // touch it (the exact test is only needed near the destination).
    if (distance(arrow.tip, result_.destination) > clear_of_circle ||
        ArrowOutline(arrow, parameters_.arrow).distanceTo(result_.destination) >= radius)
    {
      result_.tip_from_end[placed] = tip_s;
      ++placed;
    }
  }
  result_.arrows.resize(placed);
  result_.tip_from_end.resize(placed);
}

void PathSpacer::placePaper()
{
  kept_.clear();
  kept_from_end_.clear();
  const double d_min = parameters_.spacing;
  const double d_destination = parameters_.spacing + parameters_.circle_diameter;
  const std::vector<Vec2>& points = *points_in_use_;
  const std::ptrdiff_t last = static_cast<std::ptrdiff_t>(points.size()) - 1;
  std::ptrdiff_t current = last;
  do
  {
    const Vec2 p = points[static_cast<std::size_t>(current)];
    kept_.push_back(p);
    kept_from_end_.push_back(from_end_[static_cast<std::size_t>(current)]);
    const double needed = current == last ? d_destination : d_min;
    std::ptrdiff_t previous = current - 1;
    while (previous >= 0 && distance(p, points[static_cast<std::size_t>(previous)]) < needed)
    {
      --previous;
    }
    current = previous;  // -1 when the walk ran off the start (the reference's out_of_range)
  } while (current > 0);

  const std::size_t pairs = kept_.size() / 2;
  const std::size_t count = std::min(pairs, parameters_.max_arrows);
  result_.truncated = pairs > count;
  result_.arrows.resize(count);
  result_.tip_from_end.resize(count);
  for (std::size_t k = 0; k < count; ++k)
  {
    result_.arrows[k].tip = kept_[2 * k];
    result_.arrows[k].tail = kept_[2 * k + 1];
    result_.tip_from_end[k] = kept_from_end_[2 * k];
  }
}
}  // namespace rviz_projector
