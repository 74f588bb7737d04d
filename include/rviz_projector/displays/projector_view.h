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
  /// Position and orientation (w, x, y, z) of the camera, as rendered.
  std::array<float, 7> poseKey() const;

private:
  Ogre::SceneManager* scene_manager_;
  Ogre::Camera* camera_;
  Ogre::SceneNode* node_;
};
}  // namespace rviz_projector
