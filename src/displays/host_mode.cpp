#include "rviz_projector/displays/host_mode.h"

#include <atomic>

namespace rviz_projector
{
namespace
{
// One definition in the plugin library: projector_host links this library, and pluginlib loads the
// same file, so both see this flag.
std::atomic<bool> host_mode{false};
std::atomic<double> keep_alive{kHostKeepAliveSeconds};
}  // namespace

void setHostMode(bool enabled)
{
  host_mode.store(enabled, std::memory_order_relaxed);
}

void setHostKeepAliveSeconds(double seconds)
{
  keep_alive.store(seconds > 0.0 ? seconds : 0.0, std::memory_order_relaxed);
}

double hostKeepAliveSeconds()
{
  return keep_alive.load(std::memory_order_relaxed);
}

bool hostMode()
{
  return host_mode.load(std::memory_order_relaxed);
}
}  // namespace rviz_projector
