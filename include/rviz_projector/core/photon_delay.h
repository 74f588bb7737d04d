// Motion compensation (issue 14): how long after a frame's pose is looked up its light is, on
// average, on the floor. A frame appears when its rendering is done and stays up until the next
// one, so the middle of its time on screen is
//     lookup + render delay + hold / 2        (+ the projector's own input lag, added by the caller)
// where the render delay (lookup to frame handed to the screen) and the hold (time between two
// frames shown) are measured frame by frame and smoothed (exponential moving averages).
// Times are seconds on a monotonic clock; nothing here reads a clock.
#pragma once

namespace rviz_projector
{
class PhotonDelay
{
public:
  /// `smoothing`: weight of a new measurement in the moving averages (0 < smoothing <= 1).
  explicit PhotonDelay(double smoothing = 0.1);

  /// A frame whose pose was looked up at `lookup` was handed to the screen at `shown` (>= lookup).
  /// `period` is the frame period the projector aims at (s, > 0): a hold longer than two periods
  /// (the projector had nothing to draw in between) is not a hold and is not averaged.
  void frame(double lookup, double shown, double period);
  /// Forgets the measurements (output window recreated, frame rate changed).
  void clear();

  /// Smoothed render delay, s (0 before the first frame).
  double renderDelay() const { return render_; }
  /// Smoothed hold between frames, s; `period` until two consecutive frames were measured.
  double hold(double period) const { return hold_ > 0.0 ? hold_ : period; }
  /// Expected seconds from a pose lookup to the middle of the frame's time on screen.
  double expected(double period) const { return renderDelay() + 0.5 * hold(period); }

private:
  double smoothing_;
  double render_ = 0.0;
  double hold_ = 0.0;       ///< 0 until measured
  double last_shown_ = -1;  ///< < 0 before the first frame
  bool have_render_ = false;
};
}  // namespace rviz_projector
