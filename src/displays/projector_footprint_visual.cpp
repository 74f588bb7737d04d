#include "rviz_projector/displays/projector_footprint_visual.h"

#include <string>

#include <OgreManualObject.h>
#include <OgreMaterialManager.h>
#include <OgreResourceGroupManager.h>
#include <OgrePass.h>
#include <OgreSceneManager.h>
#include <OgreSceneNode.h>
#include <OgreTechnique.h>

#include "rviz_projector/displays/ogre_name.h"

namespace rviz_projector
{
namespace
{
Ogre::Vector3 toOgre(const Vec3& v)
{
  return Ogre::Vector3(static_cast<Ogre::Real>(v.x), static_cast<Ogre::Real>(v.y), static_cast<Ogre::Real>(v.z));
}
}  // namespace

ProjectorFootprintVisual::ProjectorFootprintVisual(Ogre::SceneManager* scene_manager, Ogre::SceneNode* parent)
  : scene_manager_(scene_manager)
{
  node_ = parent->createChildSceneNode();
  lines_ = scene_manager_->createManualObject(uniqueOgreName("rviz_projector_footprint_"));
  lines_->setDynamic(true);
  node_->attachObject(lines_);
  material_ = Ogre::MaterialManager::getSingleton().create(uniqueOgreName("rviz_projector_footprint_material_"), Ogre::ResourceGroupManager::DEFAULT_RESOURCE_GROUP_NAME);
  Ogre::Pass* pass = material_->getTechnique(0)->getPass(0);
  pass->setLightingEnabled(false);
  pass->setVertexColourTracking(Ogre::TVC_DIFFUSE);
}

ProjectorFootprintVisual::~ProjectorFootprintVisual()
{
  node_->detachAllObjects();
  scene_manager_->destroyManualObject(lines_);
  scene_manager_->destroySceneNode(node_);
  Ogre::MaterialManager::getSingleton().remove(material_->getName(), material_->getGroup());
}

void ProjectorFootprintVisual::update(const FloorFootprint& footprint)
{
  const Ogre::ColourValue frustum_colour(1.0f, 1.0f, 0.3f, 1.0f);
  const Ogre::ColourValue floor_colour(0.3f, 1.0f, 1.0f, 1.0f);
  // Always 8 + 2 x 32 vertices: after the first time the section and its vertex buffer are rewritten in
  // place (no allocation while the robot drives).
  if (!lines_->getSections().empty())
  {
    lines_->beginUpdate(0);
  }
  else
  {
    lines_->begin(material_->getName(), Ogre::RenderOperation::OT_LINE_LIST, material_->getGroup());
  }
  const auto& c = footprint.corners();
  for (int i = 0; i < 4; ++i)
  {
    lines_->position(toOgre(footprint.origin()));
    lines_->colour(frustum_colour);
    lines_->position(toOgre(c[i]));
    lines_->colour(frustum_colour);
  }
  // The lit area's outline: curved through a distorting lens (FloorFootprint::outline()).
  const auto& outline = footprint.outline();
  const Ogre::ColourValue& colour = footprint.complete() ? floor_colour : frustum_colour;
  for (std::size_t i = 0; i < outline.size(); ++i)
  {
    lines_->position(toOgre(outline[i]));
    lines_->colour(colour);
    lines_->position(toOgre(outline[(i + 1) % outline.size()]));
    lines_->colour(colour);
  }
  lines_->end();
}

void ProjectorFootprintVisual::setVisible(bool visible)
{
  node_->setVisible(visible);
}

void ProjectorFootprintVisual::setVisibilityFlags(std::uint32_t flags)
{
  lines_->setVisibilityFlags(flags);
}
}  // namespace rviz_projector
