#include "rviz_projector/core/frame_rate_meter.h"

#include <algorithm>
#include <cmath>

namespace rviz_projector
{
FrameRateMeter::FrameRateMeter(double window)
  : window_(std::isfinite(window) && window > 0.0 ? window : 2.0), ring_(kCapacity)
{
}

void FrameRateMeter::sample(double now, std::uint64_t total)
{
  if (!std::isfinite(now) || (count_ > 0 && now < newest().time))
  {
    return;  // not monotonic: ignored
  }
  if (count_ > 0 && total > newest().total)
  {
    last_frame_ = now;
    seen_frame_ = true;
  }
  else if (count_ == 0 && total > 0)
  {
    last_frame_ = now;  // frames before the first sample: at the latest now
    seen_frame_ = true;
  }
  if (count_ == kCapacity)  // full: the oldest goes
  {
    first_ = (first_ + 1) % kCapacity;
    --count_;
  }
  ring_[(first_ + count_) % kCapacity] = Sample{now, total};
  ++count_;
  // Keep one sample at or before the window's start, so the rate covers the whole window.
  while (count_ > 2 && at(1).time <= now - window_)
  {
    first_ = (first_ + 1) % kCapacity;
    --count_;
  }
}

double FrameRateMeter::rate(double now) const
{
  if (count_ < 2)
  {
    return 0.0;
  }
  // The count at the window's start, interpolated between the samples around it.
  const double start = std::max(now - window_, at(0).time);
  double start_total = static_cast<double>(at(0).total);
  for (std::size_t i = 1; i < count_; ++i)
  {
    const Sample& a = at(i - 1);
    const Sample& b = at(i);
    if (b.time >= start)
    {
      const double span = b.time - a.time;
      const double f = span > 0.0 ? (start - a.time) / span : 1.0;
      start_total = static_cast<double>(a.total) + f * static_cast<double>(b.total - a.total);
      break;
    }
  }
  const double elapsed = now - start;
  if (elapsed <= 0.0)
  {
    return 0.0;
  }
  return (static_cast<double>(newest().total) - start_total) / elapsed;
}

double FrameRateMeter::sinceLastFrame(double now) const
{
  return seen_frame_ ? std::max(0.0, now - last_frame_) : -1.0;
}
}  // namespace rviz_projector
