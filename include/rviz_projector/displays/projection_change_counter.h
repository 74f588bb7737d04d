// Counts changes to anything this package draws, so a projector view knows when it must render
// again (render on change instead of at a fixed rate).
#pragma once

#include <atomic>
#include <cstdint>

namespace rviz_projector
{
class ProjectionChangeCounter
{
public:
  /// Something drawn by an rviz_projector display changed (geometry, colour, visibility).
  static void bump() { counter().fetch_add(1, std::memory_order_relaxed); }
  static std::uint64_t value() { return counter().load(std::memory_order_relaxed); }

private:
  static std::atomic<std::uint64_t>& counter()
  {
    static std::atomic<std::uint64_t> count{0};
    return count;
  }
};
}  // namespace rviz_projector
