// How the projector's viewports are cleared before each frame: colour, depth and stencil together.
// Nothing draws into the stencil buffer; it is cleared because the depth buffer shares its pixels
// (packed 24-bit depth + 8-bit stencil). A depth clear alone must keep each pixel's stencil bits:
// Mesa's software renderer (llvmpipe) then reads, masks and writes every pixel of the 1280x800
// buffer on each frame (10 % of projector_host's samples under perf on the demo scene), where a
// clear of both is a plain fill (doc/dev/performance.md). On a GPU both cost the same.
#pragma once

#include <OgreViewport.h>

namespace rviz_projector
{
/// The buffers every projector viewport clears (Ogre::Viewport::setClearEveryFrame's default,
/// colour and depth, plus stencil).
constexpr unsigned kProjectorClearBuffers = Ogre::FBT_COLOUR | Ogre::FBT_DEPTH | Ogre::FBT_STENCIL;

/// Viewport::setClearEveryFrame with kProjectorClearBuffers (its own default would set colour and
/// depth only again).
inline void setProjectorClear(Ogre::Viewport& viewport, bool clear)
{
  viewport.setClearEveryFrame(clear, kProjectorClearBuffers);
}
}  // namespace rviz_projector
