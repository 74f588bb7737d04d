#include "rviz_projector/core/frame_rate_meter.h"

#include <algorithm>
#include <cmath>

namespace rviz_projector
{
FrameRateMeter::FrameRateMeter(double window) : window_(std::isfinite(window) && window > 0.0 ? window : 2.0)
{
}

void FrameRateMeter::sample(double now, std::uint64_t total)
{
  if (!std::isfinite(now) || (!samples_.empty() && now < samples_.back().time))
  {
    return;  // not monotonic: ignored
  }
  if (!samples_.empty() && total > samples_.back().total)
  {
    last_frame_ = now;
    seen_frame_ = true;
  }
  else if (samples_.empty() && total > 0)
  {
    last_frame_ = now;  // frames before the first sample: at the latest now
    seen_frame_ = true;
  }
  samples_.push_back({now, total});
  // Keep one sample at or before the window's start, so the rate covers the whole window.
  while (samples_.size() > 2 && samples_[1].time <= now - window_)
  {
    samples_.pop_front();
  }
}

double FrameRateMeter::rate(double now) const
{
  if (samples_.size() < 2)
  {
    return 0.0;
  }
  const Sample& newest = samples_.back();
  // The count at the window's start, interpolated between the samples around it.
  const double start = std::max(now - window_, samples_.front().time);
  double start_total = static_cast<double>(samples_.front().total);
  for (std::size_t i = 1; i < samples_.size(); ++i)
  {
    const Sample& a = samples_[i - 1];
    const Sample& b = samples_[i];
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
  return (static_cast<double>(newest.total) - start_total) / elapsed;
}

double FrameRateMeter::sinceLastFrame(double now) const
{
  return seen_frame_ ? std::max(0.0, now - last_frame_) : -1.0;
}
}  // namespace rviz_projector
