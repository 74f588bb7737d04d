// Drawings that change with time alone (ProjectedPath's marching arrows, blinking cues) and the
// projectors that must show each of their frames. Process-wide, on rviz's main (Qt) thread.
#pragma once

#include <vector>

#include <ros/time.h>

namespace rviz_projector
{
/// A display whose drawing depends on time. advance() brings the scene up to `now` and, when the
/// pixels change, bumps ProjectionChangeCounter (ProjectionChangeNotifier::notify): nothing
/// changes, nothing is bumped, so a still drawing costs no frames.
class AnimatedDrawing
{
public:
  virtual void advance(const ros::Time& now) = 0;

protected:
  ~AnimatedDrawing() = default;
};

/**
 * The registry. Animated displays add themselves when created and remove themselves when
 * destroyed; every ProjectorCamera calls advanceAll() at each of its frame ticks, right before it
 * decides whether to render, so an animation is computed for the time of the frame that shows it,
 * at the projector's frame rate. (Displays also advance in rviz's own update, for the main view.)
 * advance() must not add or remove drawings (it may not delete displays): it only changes scene
 * objects of its own display.
 */
class ProjectionAnimation
{
public:
  static void add(AnimatedDrawing* drawing);
  static void remove(AnimatedDrawing* drawing);
  static void advanceAll(const ros::Time& now);
  static std::size_t size() { return drawings().size(); }

private:
  static std::vector<AnimatedDrawing*>& drawings();
};
}  // namespace rviz_projector
