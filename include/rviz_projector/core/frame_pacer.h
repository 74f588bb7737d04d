// When to render the next projector frame: deadlines a whole period apart, so a millisecond timer
// delivers exactly the asked rate on average (a 16 ms timer gives 62.5 frames/s for a 60 Hz limit).
#pragma once

namespace rviz_projector
{
class FramePacer
{
public:
  /// Frames per second: the lower of the limit and the screen's refresh (when known, > 0).
  static double rate(double limit, double refresh);

  /// Seconds between frames (> 0); the phase restarts at the next tick.
  void setPeriod(double seconds);
  double period() const { return period_; }
  /**
   * The timer fired at `now` (seconds, monotonic). Returns the delay until the next deadline
   * (>= 0, <= one period). Deadlines advance by whole periods from the first tick; a tick late by
   * a period or more skips the missed deadlines instead of bursting to catch up.
   */
  double tick(double now);

private:
  double period_ = 1.0 / 60.0;
  double next_ = 0.0;
  bool started_ = false;
};
}  // namespace rviz_projector
