#include "rviz_projector/displays/floor_mesh.h"

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
FloorMesh::FloorMesh(Ogre::SceneManager* scene_manager, Ogre::SceneNode* parent)
  : scene_manager_(scene_manager)
{
  node_ = parent->createChildSceneNode();
  manual_ = scene_manager_->createManualObject(uniqueOgreName("rviz_projector_mesh_"));
  manual_->setDynamic(true);
  node_->attachObject(manual_);
  material_ = Ogre::MaterialManager::getSingleton().create(uniqueOgreName("rviz_projector_material_"), Ogre::ResourceGroupManager::DEFAULT_RESOURCE_GROUP_NAME);
  material_->setReceiveShadows(false);
  material_->setCullingMode(Ogre::CULL_NONE);
}

FloorMesh::~FloorMesh()
{
  node_->detachAllObjects();
  scene_manager_->destroyManualObject(manual_);
  scene_manager_->destroySceneNode(node_);
  Ogre::MaterialManager::getSingleton().remove(material_->getName(), material_->getGroup());
}

void FloorMesh::setMaterial(bool lit, const Ogre::ColourValue& colour)
{
  Ogre::Pass* pass = material_->getTechnique(0)->getPass(0);
  pass->setLightingEnabled(lit);
  pass->setDiffuse(colour);
  pass->setAmbient(colour * 0.5);
  pass->setSelfIllumination(lit ? colour * 0.2 : Ogre::ColourValue::Black);
  pass->setVertexColourTracking(lit ? Ogre::TVC_NONE : Ogre::TVC_DIFFUSE);
  if (colour.a < 0.9998)
  {
    pass->setSceneBlending(Ogre::SBT_TRANSPARENT_ALPHA);
    pass->setDepthWriteEnabled(false);
  }
  else
  {
    pass->setSceneBlending(Ogre::SBT_REPLACE);
    pass->setDepthWriteEnabled(true);
  }
}

void FloorMesh::beginSection(std::size_t vertex_count, bool lit)
{
  if (lit != section_lit_)
  {
    clear();  // the vertex layout differs (normals vs colours): start a fresh section
    section_lit_ = lit;
  }
  if (!has_section_)
  {
    has_section_ = true;
    manual_->estimateVertexCount(vertex_count);
    manual_->begin(material_->getName(), Ogre::RenderOperation::OT_TRIANGLE_LIST, material_->getGroup());
  }
  else
  {
    manual_->beginUpdate(0);
    manual_->estimateVertexCount(vertex_count);
  }
}

void FloorMesh::setFlatTriangles(const std::vector<Vec2>& triangles, double z, const Ogre::ColourValue& colour)
{
  if (triangles.empty())
  {
    clear();
    return;
  }
  setMaterial(false, colour);
  beginSection(triangles.size(), false);
  const Ogre::Real height = static_cast<Ogre::Real>(z);
  for (const Vec2& v : triangles)
  {
    manual_->position(static_cast<Ogre::Real>(v.x), static_cast<Ogre::Real>(v.y), height);
    manual_->colour(colour);
  }
  manual_->end();
  triangle_count_ = triangles.size() / 3;
}

void FloorMesh::setSolidTriangles(const std::vector<MeshVertex>& triangles, double z,
                                  const Ogre::ColourValue& colour)
{
  if (triangles.empty())
  {
    clear();
    return;
  }
  setMaterial(true, colour);
  beginSection(triangles.size(), true);
  for (const MeshVertex& v : triangles)
  {
    manual_->position(static_cast<Ogre::Real>(v.position.x), static_cast<Ogre::Real>(v.position.y),
                      static_cast<Ogre::Real>(v.position.z + z));
    manual_->normal(static_cast<Ogre::Real>(v.normal.x), static_cast<Ogre::Real>(v.normal.y),
                    static_cast<Ogre::Real>(v.normal.z));
  }
  manual_->end();
  triangle_count_ = triangles.size() / 3;
}

void FloorMesh::clear()
{
  manual_->clear();
  has_section_ = false;
  triangle_count_ = 0;
}
}  // namespace rviz_projector
