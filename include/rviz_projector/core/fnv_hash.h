// FNV-1a, 64 bit: the one hash of the change signatures (scene, visibility ticks). Not for
// security; fast and good enough to tell "anything changed" apart from "nothing changed".
#pragma once

#include <cstddef>
#include <cstdint>

namespace rviz_projector
{
constexpr std::uint64_t kFnvOffsetBasis = 14695981039346656037ull;

/// Mixes `size` bytes at `data` into `hash`.
inline void fnv1aMix(std::uint64_t& hash, const void* data, std::size_t size)
{
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i)
  {
    hash ^= bytes[i];
    hash *= 1099511628211ull;
  }
}

/// Mixes the 8 bytes of `value` (in memory order) into `hash`.
inline void fnv1aMix(std::uint64_t& hash, std::uint64_t value)
{
  fnv1aMix(hash, &value, sizeof value);
}
}  // namespace rviz_projector
