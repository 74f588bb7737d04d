// One part of ProjectorCameraDisplay: the OGRE camera that sees the scene as the projector does,
// at the projector's pose and through its lens (PinholeModel's exact projection matrix).
#pragma once

#include <array>
#include <string>

#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/displays/projector_pose.h"

namespace Ogre
{
class Camera;
class SceneManager;
class SceneNode;
}  // namespace Ogre

namespace rviz_projector
{
class ProjectorView
{
public:
  explicit ProjectorView(Ogre::SceneManager* scene_manager);
  ~ProjectorView();
  ProjectorView(const ProjectorView&) = delete;
  ProjectorView& operator=(const ProjectorView&) = delete;

  Ogre::Camera* camera() const { return camera_; }
  /**
   * Projection of `lens` (nullptr: none yet, OGRE's default) between the clip distances, metres.
   * Returns a warning when far_clip is not beyond near_clip (then 1000 x near_clip is used).
   */
  std::string setProjection(const PinholeModel* lens, double near_clip, double far_clip);
  /// Puts the camera at the projector's optical frame (pose.state must be Ok).
  void setPose(const ProjectorPose& pose);

  /// Max lit height: nothing of the scene above z = `height` of the fixed frame is drawn (the plane
  /// becomes the projection's near plane, applyObliqueNearPlane). NaN or <= 0: off.
  void setMaxLitHeight(double height);
  enum class Ceiling
  {
    Off,             ///< no Max lit height
    Clipping,        ///< the projector is above the height: everything above it is clipped
    ProjectorBelow,  ///< the projector is not above the height: nothing is clipped (doc/guide/safety-mask.md)
    NoLens,          ///< no lens yet
  };
  Ceiling ceiling() const { return ceiling_; }
  /// Position and orientation (w, x, y, z) of the camera, as rendered.
  std::array<float, 7> poseKey() const;

private:
  /// The lens's projection, with the Max lit height plane for the current pose when it is on.
  void applyProjection();

  Ogre::SceneManager* scene_manager_;
  bool has_lens_ = false;
  std::array<double, 16> lens_projection_{};
  double max_lit_height_ = 0.0;  // <= 0: off
  Ceiling ceiling_ = Ceiling::Off;
  Ogre::Camera* camera_;
  Ogre::SceneNode* node_;
};
}  // namespace rviz_projector
