#include "rviz_projector/core/frame_pacer.h"

#include <algorithm>
#include <cmath>

namespace rviz_projector
{
double FramePacer::rate(double limit, double refresh)
{
  const double wanted = std::isfinite(limit) && limit > 0.0 ? limit : 60.0;
  return std::isfinite(refresh) && refresh > 1.0 ? std::min(wanted, refresh) : wanted;
}

void FramePacer::setPeriod(double seconds)
{
  period_ = std::isfinite(seconds) && seconds > 1e-6 ? seconds : 1.0 / 60.0;
  started_ = false;
}

double FramePacer::tick(double now)
{
  if (!started_ || !std::isfinite(next_))
  {
    started_ = true;
    next_ = now;
  }
  next_ += period_;
  if (next_ <= now)
  {
    next_ = now + period_;  // fell a whole period behind: skip, do not burst
  }
  return std::min(period_, std::max(0.0, next_ - now));
}
}  // namespace rviz_projector
