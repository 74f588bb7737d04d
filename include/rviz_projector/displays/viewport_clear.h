// How the projector's viewports are cleared before each frame: colour, depth and stencil together.
// Nothing draws into the stencil buffer; it is cleared because the depth buffer shares its pixels
// (packed 24-bit depth + 8-bit stencil). A depth clear alone must keep each pixel's stencil bits:
// Mesa's software renderer (llvmpipe) then reads, masks and writes every pixel of the 1280x800
// buffer on each frame (10 % of projector_host's samples under perf on the demo scene), where a
// clear of both is a plain fill (doc/dev/performance.md). On a GPU both cost the same.
// Through a distorting lens the window only shows the warp's mesh, which tests no depth: there
// the window clears its colour alone, or nothing where the mesh covers all of it.
#pragma once

#include <OgreViewport.h>

namespace rviz_projector
{
/// The buffers every projector viewport clears (Ogre::Viewport::setClearEveryFrame's default,
/// colour and depth, plus stencil).
constexpr unsigned kProjectorClearBuffers = Ogre::FBT_COLOUR | Ogre::FBT_DEPTH | Ogre::FBT_STENCIL;

/// What the window clears under the warp's occupied cells (software renderer): the colour of the
/// cells it does not draw. Its depth buffer is not used while it shows the warp.
constexpr unsigned kWarpCellsClearBuffers = Ogre::FBT_COLOUR;

/// What the ideal render's texture clears when the warp's eraser (warp_eraser.h) has put its colour
/// back to the background where the last frame lit it: depth and stencil (together: a plain fill).
constexpr unsigned kErasedTextureClearBuffers = Ogre::FBT_DEPTH | Ogre::FBT_STENCIL;

/// The buffers `viewport` clears each frame (0: it is not cleared).
inline unsigned clearedBuffers(const Ogre::Viewport& viewport)
{
  return viewport.getClearEveryFrame() ? viewport.getClearBuffers() : 0u;
}

/// Makes `viewport` clear `buffers` each frame (0: nothing), touching it only when that changes
/// (Viewport::setClearEveryFrame's own default would set colour and depth only).
inline void setClearedBuffers(Ogre::Viewport& viewport, unsigned buffers)
{
  if (clearedBuffers(viewport) != buffers)
  {
    viewport.setClearEveryFrame(buffers != 0u, buffers);
  }
}
}  // namespace rviz_projector
