// One part of DistortionWarp (issue 24, occupied cells on a software renderer): puts the ideal
// render's texture back to its background where the last frame lit it, instead of clearing all of
// it. On llvmpipe a colour clear of the 1382x864 texture is a fill of 4.8 MB (0.6-0.7 ms per frame);
// a projector's picture is mostly background, and the warp reads every frame's render back anyway
// (warp_cells.h), so it knows which 8x8 blocks hold anything else. The eraser paints those blocks
// in the background's exact bytes, in a viewport of its own drawn before the scene's (its own scene
// and camera: nothing of rviz's scene), and the scene's viewport then clears depth and stencil only.
// What it paints is chosen by its owner; this part only draws it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <OgreMaterial.h>

#include "rviz_projector/core/warp_cells.h"

namespace Ogre
{
class Camera;
class ManualObject;
class RenderTexture;
class SceneManager;
class Viewport;
}  // namespace Ogre

namespace rviz_projector
{
class WarpEraser
{
public:
  WarpEraser();
  ~WarpEraser();
  WarpEraser(const WarpEraser&) = delete;
  WarpEraser& operator=(const WarpEraser&) = delete;

  /// Draws into `target` (width x height pixels) before its other viewports (a lower z-order);
  /// clears nothing itself. Null: detached (the viewport removed from the earlier target).
  void attach(Ogre::RenderTexture* target, std::uint32_t width, std::uint32_t height);
  /// This frame paints `rects` (pixels of the target, rows from the top) in `rgba`, bytes as the
  /// target stores them after a clear to that colour; no rectangles: paints nothing.
  void paint(const std::vector<TexelRect>& rects, const std::array<std::uint8_t, 4>& rgba);

private:
  Ogre::SceneManager* scene_;
  Ogre::Camera* camera_;
  Ogre::ManualObject* mesh_;
  Ogre::MaterialPtr material_;
  Ogre::RenderTexture* target_ = nullptr;
  Ogre::Viewport* viewport_ = nullptr;
  std::uint32_t width_ = 1, height_ = 1;
  bool written_ = false;
  // What the mesh holds (a frame like the last one is not written again).
  std::vector<TexelRect> written_rects_;
  std::array<std::uint8_t, 4> written_rgba_{{0, 0, 0, 0}};
};

/// The bytes a render target of 8 bits per channel holds after a clear to (r, g, b, a): core unorm8
/// of each.
std::array<std::uint8_t, 4> clearedBytes(float r, float g, float b, float a);
}  // namespace rviz_projector
