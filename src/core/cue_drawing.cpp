#include "rviz_projector/core/cue_drawing.h"

#include <algorithm>
#include <cmath>

#include "rviz_projector/core/arrow_outline.h"
#include "rviz_projector/core/disc_outline.h"
#include "rviz_projector/core/path_horizon.h"
#include "rviz_projector/core/path_location.h"

namespace rviz_projector
{
namespace
{
/// Width of the cross's bars, as a fraction of the circle's diameter.
constexpr double kCrossWidthFraction = 0.2;
}  // namespace

void CueDrawing::build(const std::vector<Vec2>& path, const SpacedPath& spaced, const SpacingParameters& parameters,
                       const PathCueSettings& settings, const PathCueInput& input)
{
  arrows_.clear();
  arrow_alpha_.clear();
  destination_.clear();
  glyph_.clear();
  turn_ = TurnDetection();
  cross_ = false;
  destination_alpha_ = 1.0f;
  animating_ = input.goal.animating;
  horizon_start_ = 0.0;

  accumulateArcLengths(path, lengths_);
  const double length = spaced.path_length;
  double robot_arc = 0.0;
  if (input.robot_known && isFinite(input.robot) && !path.empty())
  {
    const PathLocation here = locateOnPath(path, lengths_, input.robot);
    if (here.valid)
    {
      robot_arc = here.arc_length;
    }
  }
  robot_arc_ = robot_arc;
  HorizonWindow window;
  if (settings.horizon)
  {
    window = makeHorizon(robot_arc, settings.horizon_length, settings.fade_length);
    horizon_start_ = window.start;
  }

  if (input.goal.arrows)
  {
    for (std::size_t i = 0; i < spaced.arrows.size(); ++i)
    {
      const double from_end = i < spaced.tip_from_end.size() ? spaced.tip_from_end[i] : 0.0;
      const double alpha = window.alpha(length - from_end);
      if (!(alpha > 0.0))
      {
        continue;
      }
      const ArrowOutline outline(spaced.arrows[i], parameters.arrow);
      if (!outline.valid())
      {
        continue;
      }
      outline.appendTriangles(arrows_);
      arrow_alpha_.resize(arrows_.size(), static_cast<float>(alpha));
    }
  }
  if (input.goal.destination && spaced.has_destination)
  {
    const double alpha = window.alpha(length);
    if (alpha > 0.0)
    {
      destination_alpha_ = static_cast<float>(alpha);
      cross_ = input.goal.cross;
      if (cross_)
      {
        appendCross(spaced.destination, parameters.circle_diameter,
                    parameters.circle_diameter * kCrossWidthFraction, destination_);
      }
      else
      {
        DiscOutline(spaced.destination, parameters.circle_diameter).appendTriangles(destination_);
      }
    }
  }
  if (settings.turn_signal && input.robot_known && input.goal.arrows && path.size() >= 2)
  {
    turn_ = detectTurn(path, lengths_, robot_arc, settings.turn);
    if (turn_.side != TurnSide::None)
    {
      animating_ = true;
      if (blinkOn(input.time, settings.turn_hz))
      {
        appendTurnGlyph(input.robot, turn_.heading, turn_.side, settings.glyph_ahead, settings.glyph_aside,
                        settings.glyph_size, glyph_);
      }
    }
  }
  if (settings.corridor && input.goal.arrows && path.size() >= 2)
  {
    CorridorKey key{path.data(), path.size(), path.front(), path.back(), robot_arc,
                    settings.corridor_radius, settings.corridor_footprint, settings.corridor_parameters};
    if (!(key == corridor_key_))
    {
      if (settings.corridor_radius > 0.0)
      {
        corridor_.buildRound(path, lengths_, robot_arc, settings.corridor_radius, settings.corridor_parameters);
      }
      else
      {
        corridor_.build(path, lengths_, robot_arc, settings.corridor_footprint, settings.corridor_parameters);
      }
      corridor_key_ = std::move(key);
    }
  }
  else if (corridor_key_.path != nullptr || !corridor_.band().empty())
  {
    corridor_.build({}, {}, 0.0, {}, CorridorParameters());  // empty
    corridor_key_ = CorridorKey();
  }
  if (settings.stop_zone && input.goal.arrows)
  {
    stop_zone_.build(path, lengths_, robot_arc, input.speed, settings.stop);
  }
  else
  {
    stop_zone_.build(path, lengths_, robot_arc, SpeedEstimate(), settings.stop);  // empty
  }
  if (settings.marching && settings.marching_speed > 0.0 && parameters.mode == SpacingMode::Exact)
  {
    animating_ = true;
  }
}

std::size_t CueDrawing::arrowsDrawn() const
{
  return arrows_.size() / ArrowOutline::kVerticesPerArrow;
}
}  // namespace rviz_projector

namespace rviz_projector
{
bool CueDrawing::CorridorKey::operator==(const CorridorKey& o) const
{
  auto same = [](const Vec2& a, const Vec2& b) { return a.x == b.x && a.y == b.y; };
  const CorridorParameters& p = parameters;
  const CorridorParameters& q = o.parameters;
  return path == o.path && path_size == o.path_size && same(first, o.first) && same(last, o.last) &&
         robot_arc == o.robot_arc && radius == o.radius && footprint.size() == o.footprint.size() &&
         std::equal(footprint.begin(), footprint.end(), o.footprint.begin(), same) && p.length == q.length &&
         p.edge_width == q.edge_width && p.step == q.step && p.turn_step == q.turn_step &&
         p.heading_chord == q.heading_chord;
}
}  // namespace rviz_projector
