#include "rviz_projector/core/data_age.h"

#include <cmath>

namespace rviz_projector
{
double dataAge(double stamp, double now)
{
  if (stamp == 0.0 || !std::isfinite(stamp) || !std::isfinite(now))
  {
    return 0.0;
  }
  return now > stamp ? now - stamp : 0.0;
}

bool isFromTheFuture(double stamp, double now, double timeout)
{
  return stamp != 0.0 && std::isfinite(stamp) && std::isfinite(now) && std::isfinite(timeout) && timeout > 0.0 &&
         stamp - now > timeout;
}

bool isStale(double age, double timeout)
{
  return std::isfinite(timeout) && timeout > 0.0 && age > timeout;
}
}  // namespace rviz_projector
