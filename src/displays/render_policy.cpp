#include "rviz_projector/displays/render_policy.h"

#include <atomic>

namespace rviz_projector
{
namespace
{
// One definition in the plugin library: projector_host links this library, and pluginlib loads the
// same file, so both see this value. Written once, before any display exists.
std::atomic<bool> host{false};
std::atomic<double> keep_alive{kHostKeepAliveSeconds};
}  // namespace

RenderPolicy processRenderPolicy()
{
  RenderPolicy policy;
  policy.host = host.load(std::memory_order_relaxed);
  policy.keep_alive_s = keep_alive.load(std::memory_order_relaxed);
  return policy;
}

void setProcessRenderPolicy(const RenderPolicy& policy)
{
  keep_alive.store(policy.keep_alive_s > 0.0 ? policy.keep_alive_s : 0.0, std::memory_order_relaxed);
  host.store(policy.host, std::memory_order_relaxed);
}
}  // namespace rviz_projector
