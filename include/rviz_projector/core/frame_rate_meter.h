// Frames actually rendered per second, over a rolling window: fed with the running count of
// rendered frames whenever the caller looks (e.g. at each frame timer tick), so it needs no hook
// where the frames are rendered. Times are seconds on a monotonic clock.
#pragma once

#include <cstdint>
#include <deque>

namespace rviz_projector
{
class FrameRateMeter
{
public:
  /// `window`: seconds of history the rate is measured over (> 0).
  explicit FrameRateMeter(double window = 2.0);

  /// At time `now` the caller had rendered `total` frames in all (a count that only grows).
  void sample(double now, std::uint64_t total);
  /// Frames per second over the last `window` seconds before `now` (over the time since the first
  /// sample while that is shorter); 0 before two samples.
  double rate(double now) const;
  /// Seconds since the count last grew (a frame was rendered); < 0 when no frame was seen yet.
  double sinceLastFrame(double now) const;

private:
  struct Sample
  {
    double time;
    std::uint64_t total;
  };
  double window_;
  std::deque<Sample> samples_;  ///< oldest first; the oldest may lie just before the window
  double last_frame_ = -1.0;
  bool seen_frame_ = false;
};
}  // namespace rviz_projector
