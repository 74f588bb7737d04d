// One part of ProjectorCameraDisplay (issue 24): drawing through a distorting lens. The scene is
// rendered by the projector's camera as the ideal pinhole of a WarpGrid (core) into a texture,
// and a mesh of the grid's cells, in a scene of its own, draws that texture into the output
// window where each raw pixel's ray lands. With no distortion nothing here exists (no texture, no
// extra pass): the projector's camera draws into the window as before.
#pragma once

#include <cstdint>
#include <string>

#include <OgreColourValue.h>
#include <OgreMaterial.h>
#include <OgreTexture.h>

#include "rviz_projector/core/lens_distortion.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/warp_grid.h"

namespace Ogre
{
class Camera;
class ManualObject;
class RenderTargetListener;
class RenderTexture;
class SceneManager;
class Viewport;
}  // namespace Ogre

namespace rviz_projector
{
class DistortionWarp
{
public:
  /// `scene_camera` renders the ideal view into the texture; `listener` hears that render (it
  /// refreshes the visibility bits before it, as for the window). Both outlive this object.
  DistortionWarp(Ogre::Camera* scene_camera, Ogre::RenderTargetListener* listener);
  ~DistortionWarp();
  DistortionWarp(const DistortionWarp&) = delete;
  DistortionWarp& operator=(const DistortionWarp&) = delete;

  /// For a raw lens (K's pinhole of the projector's pixels) and its distortion: none -> off (all
  /// released). Returns an error text when the texture cannot be made (the warp is then off).
  std::string configure(const PinholeModel& raw_lens, const LensDistortion& distortion);
  /// Releases everything: no distortion.
  void clear();

  bool active() const { return render_texture_ != nullptr; }
  /// The pinhole the scene camera must render with while active (the grid's ideal lens).
  const PinholeModel& idealLens() const { return grid_.ideal_lens; }
  const WarpGrid& grid() const { return grid_; }
  /// Largest interpolation error of the grid, raw pixels (core warpGridError).
  double gridError() const { return grid_error_; }
  /// The camera that draws the warped picture (into the output window's viewport).
  Ogre::Camera* warpCamera() const { return warp_camera_; }

  void setBackground(const Ogre::ColourValue& colour);
  void setVisibilityMask(std::uint32_t mask);
  /// Renders the ideal view into the texture (before the window's render).
  void renderIdeal();

private:
  Ogre::Camera* scene_camera_;
  Ogre::RenderTargetListener* listener_;
  Ogre::SceneManager* warp_scene_;
  Ogre::Camera* warp_camera_;
  Ogre::ManualObject* mesh_;
  Ogre::MaterialPtr material_;
  Ogre::TexturePtr texture_;
  Ogre::RenderTexture* render_texture_ = nullptr;
  Ogre::Viewport* viewport_ = nullptr;
  Ogre::ColourValue background_ = Ogre::ColourValue::Black;
  std::uint32_t visibility_mask_ = 0xFFFFFFFFu;
  WarpGrid grid_;
  double grid_error_ = 0.0;
};
}  // namespace rviz_projector
