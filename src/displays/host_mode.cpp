#include "rviz_projector/displays/host_mode.h"

#include <atomic>

namespace rviz_projector
{
namespace
{
// One definition in the plugin library: projector_host links this library, and pluginlib loads the
// same file, so both see this flag.
std::atomic<bool> host_mode{false};
std::atomic<std::uint64_t> render_requests{0};
}  // namespace

void countHostRenderRequest()
{
  render_requests.fetch_add(1, std::memory_order_relaxed);
}

std::uint64_t hostRenderRequests()
{
  return render_requests.load(std::memory_order_relaxed);
}

void setHostMode(bool enabled)
{
  host_mode.store(enabled, std::memory_order_relaxed);
}

bool hostMode()
{
  return host_mode.load(std::memory_order_relaxed);
}
}  // namespace rviz_projector
