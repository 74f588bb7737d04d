#include "rviz_projector/core/photon_delay.h"

#include <algorithm>
#include <cmath>

namespace rviz_projector
{
PhotonDelay::PhotonDelay(double smoothing) : smoothing_(std::clamp(smoothing, 1e-3, 1.0))
{
}

void PhotonDelay::clear()
{
  render_ = 0.0;
  hold_ = 0.0;
  last_shown_ = -1.0;
  have_render_ = false;
}

void PhotonDelay::frame(double lookup, double shown, double period)
{
  const double delay = shown - lookup;
  if (!std::isfinite(delay) || delay < 0.0 || !std::isfinite(shown))
  {
    return;
  }
  render_ = have_render_ ? render_ + smoothing_ * (delay - render_) : delay;
  have_render_ = true;
  if (last_shown_ >= 0.0)
  {
    const double hold = shown - last_shown_;
    if (hold > 0.0 && std::isfinite(period) && hold <= 2.0 * period)  // longer: nothing was drawn between
    {
      hold_ = hold_ > 0.0 ? hold_ + smoothing_ * (hold - hold_) : hold;
    }
  }
  last_shown_ = shown;
}
}  // namespace rviz_projector
