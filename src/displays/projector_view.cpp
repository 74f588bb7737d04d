#include "rviz_projector/displays/projector_view.h"

#include <cmath>
#include <cstdio>

#include <OgreCamera.h>
#include <OgreMatrix3.h>
#include <OgreMatrix4.h>
#include <OgreSceneManager.h>
#include <OgreSceneNode.h>

#include "rviz_projector/core/projection_mask.h"
#include "rviz_projector/displays/ogre_name.h"

namespace rviz_projector
{
ProjectorView::ProjectorView(Ogre::SceneManager* scene_manager)
  : scene_manager_(scene_manager), camera_(scene_manager->createCamera(uniqueOgreName("rviz_projector_camera_")))
{
  node_ = scene_manager_->getRootSceneNode()->createChildSceneNode();
  node_->attachObject(camera_);
}

ProjectorView::~ProjectorView()
{
  node_->detachAllObjects();
  scene_manager_->destroySceneNode(node_);
  scene_manager_->destroyCamera(camera_);
}

std::string ProjectorView::setProjection(const PinholeModel* lens, double near_clip, double far_clip)
{
  std::string warning;
  if (!(far_clip > near_clip))
  {
    far_clip = near_clip * 1000.0;
    char text[128];
    std::snprintf(text, sizeof text, "Far clip must be beyond near clip: using %g m", far_clip);
    warning = text;
  }
  camera_->setNearClipDistance(static_cast<Ogre::Real>(near_clip));
  camera_->setFarClipDistance(static_cast<Ogre::Real>(far_clip));
  has_lens_ = lens != nullptr;
  if (lens)
  {
    lens_projection_ = lens->glProjectionMatrix(near_clip, far_clip);
    applyProjection();
  }
  return warning;
}

void ProjectorView::setMaxLitHeight(double height)
{
  max_lit_height_ = std::isfinite(height) && height > 0.0 ? height : 0.0;
  applyProjection();
}

void ProjectorView::applyProjection()
{
  if (!has_lens_)
  {
    ceiling_ = max_lit_height_ > 0.0 ? Ceiling::NoLens : Ceiling::Off;
    return;
  }
  std::array<double, 16> m = lens_projection_;
  ceiling_ = Ceiling::Off;
  if (max_lit_height_ > 0.0)
  {
    // The plane z <= h of the fixed frame in camera coordinates: a camera point v is at R v + p, so
    // h - z = -(row 2 of R) . v + (h - p.z) >= 0.
    Ogre::Matrix3 r;
    node_->getOrientation().ToRotationMatrix(r);
    const Ogre::Vector3& p = node_->getPosition();
    const std::array<double, 4> plane{-r[2][0], -r[2][1], -r[2][2], max_lit_height_ - p.z};
    ceiling_ = applyObliqueNearPlane(m, plane) ? Ceiling::Clipping : Ceiling::ProjectorBelow;
  }
  Ogre::Matrix4 projection;
  for (int row = 0; row < 4; ++row)
  {
    for (int c = 0; c < 4; ++c)
    {
      projection[row][c] = static_cast<Ogre::Real>(m[4 * row + c]);
    }
  }
  camera_->setCustomProjectionMatrix(true, projection);
}

void ProjectorView::setPose(const ProjectorPose& pose)
{
  const Vec3& p = pose.optical_to_fixed.translation();
  // Optical frame (z forward, y down) -> OGRE camera (looks down -z, y up): half turn about x.
  const Ogre::Quaternion optical(static_cast<Ogre::Real>(pose.qw), static_cast<Ogre::Real>(pose.qx),
                                 static_cast<Ogre::Real>(pose.qy), static_cast<Ogre::Real>(pose.qz));
  const Ogre::Vector3 position(static_cast<Ogre::Real>(p.x), static_cast<Ogre::Real>(p.y), static_cast<Ogre::Real>(p.z));
  const Ogre::Quaternion orientation = optical * Ogre::Quaternion(Ogre::Degree(180), Ogre::Vector3::UNIT_X);
  // The same pose again (a still robot): touching the node would queue a scene update (an
  // allocation in OGRE) every frame for nothing.
  if (position == node_->getPosition() && orientation == node_->getOrientation())
  {
    return;
  }
  node_->setPosition(position);
  node_->setOrientation(orientation);
  if (max_lit_height_ > 0.0)
  {
    applyProjection();  // the clipping plane is fixed in the world, not in the camera
  }
}

std::array<float, 7> ProjectorView::poseKey() const
{
  const Ogre::Vector3& p = node_->getPosition();
  const Ogre::Quaternion& q = node_->getOrientation();
  return {p.x, p.y, p.z, q.w, q.x, q.y, q.z};
}
}  // namespace rviz_projector
