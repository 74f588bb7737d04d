// In rviz's main view: the projector's frustum and the quadrilateral it lights on the floor.
#pragma once

#include <cstdint>

#include <OgreMaterial.h>

#include "rviz_projector/core/floor_footprint.h"

namespace Ogre
{
class ManualObject;
class SceneManager;
class SceneNode;
}  // namespace Ogre

namespace rviz_projector
{
class ProjectorFootprintVisual
{
public:
  ProjectorFootprintVisual(Ogre::SceneManager* scene_manager, Ogre::SceneNode* parent);
  ~ProjectorFootprintVisual();
  ProjectorFootprintVisual(const ProjectorFootprintVisual&) = delete;
  ProjectorFootprintVisual& operator=(const ProjectorFootprintVisual&) = delete;

  /// Draws the frustum edges (lens to corners) and, where complete, the floor outline.
  void update(const FloorFootprint& footprint);
  void setVisible(bool visible);
  /// Ogre visibility flags of the lines (the projector's own view must not see them).
  void setVisibilityFlags(std::uint32_t flags);

private:
  Ogre::SceneManager* scene_manager_;
  Ogre::SceneNode* node_;
  Ogre::ManualObject* lines_;
  Ogre::MaterialPtr material_;
};
}  // namespace rviz_projector
