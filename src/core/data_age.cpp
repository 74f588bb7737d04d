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

bool isStale(double age, double timeout)
{
  return std::isfinite(timeout) && timeout > 0.0 && age > timeout;
}
}  // namespace rviz_projector
