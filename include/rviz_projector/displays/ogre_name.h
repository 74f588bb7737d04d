// OGRE object names (materials, meshes, cameras) must be unique in the process: several instances
// of a display, or a display removed and added again, must never reuse one.
#pragma once

#include <atomic>
#include <string>

namespace rviz_projector
{
inline std::string uniqueOgreName(const char* prefix)
{
  static std::atomic<unsigned> counter{0};
  return std::string(prefix) + std::to_string(counter++);
}
}  // namespace rviz_projector
