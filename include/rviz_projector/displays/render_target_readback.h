// Copies a rendered OGRE target into memory (for the optional Image output and for tests).
#pragma once

#include <cstdint>
#include <vector>

namespace Ogre
{
class RenderTarget;
}

namespace rviz_projector
{
/// RGB, 8 bits per channel, rows top to bottom, from the back buffer (call before swapping).
/// Returns false when the target has no pixels.
bool readRgbPixels(Ogre::RenderTarget* target, std::vector<std::uint8_t>& rgb, unsigned& width, unsigned& height);
}  // namespace rviz_projector
