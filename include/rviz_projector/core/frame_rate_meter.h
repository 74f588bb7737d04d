// Frames actually rendered per second, over a rolling window: fed with the running count of
// rendered frames whenever the caller looks (e.g. at each frame timer tick), so it needs no hook
// where the frames are rendered. Times are seconds on a monotonic clock. The samples live in a
// ring buffer allocated once: sampling allocates nothing (it runs every projector frame).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rviz_projector
{
class FrameRateMeter
{
public:
  /// `window`: seconds of history the rate is measured over (> 0).
  explicit FrameRateMeter(double window = 2.0);

  /// Samples kept at most: the window holds them when sampled at up to kCapacity / window per
  /// second (512 Hz for 2 s); beyond that the oldest go first and the rate covers a shorter time.
  static constexpr std::size_t kCapacity = 1024;

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
  /// i-th sample, oldest first; the oldest may lie just before the window.
  const Sample& at(std::size_t i) const { return ring_[(first_ + i) % kCapacity]; }
  const Sample& newest() const { return at(count_ - 1); }

  double window_;
  std::vector<Sample> ring_;  ///< kCapacity entries from construction on
  std::size_t first_ = 0;     ///< ring index of the oldest sample
  std::size_t count_ = 0;     ///< samples held
  double last_frame_ = -1.0;
  bool seen_frame_ = false;
};
}  // namespace rviz_projector
