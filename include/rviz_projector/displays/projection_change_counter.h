// Counts changes to anything this package draws, so a projector view knows when it must render
// again (render on change instead of at a fixed rate).
#pragma once

#include <atomic>
#include <cstdint>

namespace rviz_projector
{
/**
 * One process-wide counter of "something an rviz_projector display draws has changed".
 *
 * Who bumps it, and when: every display of this package whose drawing a ProjectorCamera shows
 * (today ProjectedPathDisplay) calls bump() once after each change that alters its pixels, right
 * after the scene was changed and before the next render: new meshes (a path, a style or colour
 * change), enable and disable (its scene node shown or hidden), reset when it clears its meshes.
 * Changes of other displays (rviz's own) are not counted here: the projector detects those itself
 * (visibility signature, its own change count).
 *
 * What a reader may assume:
 * - Monotonic: value() never decreases; each bump() adds exactly 1 (no wrap in practice: 2^64).
 * - Process-wide: one counter for every display and every ProjectorCamera of the process, whatever
 *   library or executable calls it (a single object behind an inline function).
 * - Equality only: "value() differs from the value I saw at my last render" means "render again";
 *   the difference says nothing about how many displays changed or what. Readers keep their own
 *   last-seen value and never reset the counter (there is no reset).
 * - Thread: displays bump and projectors read on rviz's main (Qt GUI) thread, where the scene
 *   changes. bump() and value() are atomic, so a call from another thread is never lost or torn,
 *   but they order nothing else (relaxed): a reader on another thread must not assume the scene
 *   change behind a bump is visible to it.
 */
class ProjectionChangeCounter
{
public:
  /// Something drawn by an rviz_projector display changed (geometry, colour, visibility).
  static void bump() { counter().fetch_add(1, std::memory_order_relaxed); }
  /// The number of bumps so far in this process; compare with a value seen earlier.
  static std::uint64_t value() { return counter().load(std::memory_order_relaxed); }

private:
  static std::atomic<std::uint64_t>& counter()
  {
    static std::atomic<std::uint64_t> count{0};
    return count;
  }
};
}  // namespace rviz_projector
