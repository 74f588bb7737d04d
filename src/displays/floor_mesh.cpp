#include "rviz_projector/displays/floor_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <OgreMaterialManager.h>
#include <OgreRenderQueue.h>
#include <OgrePass.h>
#include <OgreResourceGroupManager.h>
#include <OgreSceneManager.h>
#include <OgreSceneNode.h>
#include <OgreTechnique.h>
#include <rviz/ogre_helpers/compatibility.h>

#include "rviz_projector/displays/floor_mesh_renderable.h"
#include "rviz_projector/displays/ogre_name.h"

namespace rviz_projector
{
namespace
{
/// Grows a bounding box by points, without Ogre::AxisAlignedBox::merge's per-point checks.
class Bounds
{
public:
  void add(float x, float y, float z)
  {
    min_x_ = std::min(min_x_, x);
    min_y_ = std::min(min_y_, y);
    min_z_ = std::min(min_z_, z);
    max_x_ = std::max(max_x_, x);
    max_y_ = std::max(max_y_, y);
    max_z_ = std::max(max_z_, z);
  }
  Ogre::AxisAlignedBox box() const
  {
    if (!(min_x_ <= max_x_ && min_y_ <= max_y_ && min_z_ <= max_z_))
    {
      return Ogre::AxisAlignedBox();  // null: nothing (finite) was added
    }
    return Ogre::AxisAlignedBox(min_x_, min_y_, min_z_, max_x_, max_y_, max_z_);
  }

private:
  float min_x_ = HUGE_VALF, min_y_ = HUGE_VALF, min_z_ = HUGE_VALF;
  float max_x_ = -HUGE_VALF, max_y_ = -HUGE_VALF, max_z_ = -HUGE_VALF;
};
}  // namespace

FloorMesh::FloorMesh(Ogre::SceneManager* scene_manager, Ogre::SceneNode* parent)
  : scene_manager_(scene_manager), renderable_(std::make_unique<FloorMeshRenderable>())
{
  node_ = parent->createChildSceneNode();
  material_ = Ogre::MaterialManager::getSingleton().create(uniqueOgreName("rviz_projector_material_"), Ogre::ResourceGroupManager::DEFAULT_RESOURCE_GROUP_NAME);
  material_->setReceiveShadows(false);
  material_->setCullingMode(Ogre::CULL_NONE);
  rviz::setMaterial(*renderable_, material_);
  node_->attachObject(renderable_.get());
}

FloorMesh::~FloorMesh()
{
  node_->detachAllObjects();
  scene_manager_->destroySceneNode(node_);
  renderable_.reset();
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

void FloorMesh::setFlatTriangles(const std::vector<Vec2>& triangles, double z, const Ogre::ColourValue& colour)
{
  static const std::vector<float> kOpaque;
  setFlatTriangles(triangles, kOpaque, z, colour);
}

void FloorMesh::setFlatTriangles(const std::vector<Vec2>& triangles, const std::vector<float>& alpha, double z,
                                 const Ogre::ColourValue& colour)
{
  if (triangles.empty())
  {
    clear();
    return;
  }
  const float lowest = alpha.empty() ? 1.0f : std::min(1.0f, *std::min_element(alpha.begin(), alpha.end()));
  Ogre::ColourValue material_colour = colour;
  material_colour.a = colour.a * std::max(0.0f, lowest);
  setMaterial(false, material_colour);  // blending on when any vertex is translucent
  const Ogre::VertexElementType colour_type = Ogre::VertexElement::getBestColourVertexElementType();
  const std::uint32_t packed = Ogre::VertexElement::convertColourValue(colour, colour_type);
  const float height = static_cast<float>(z);
  Bounds bounds;
  float* out = renderable_->lock(triangles.size(), FloorMeshRenderable::Layout::PositionColour);
  for (std::size_t i = 0; i < triangles.size(); ++i)
  {
    const Vec2& v = triangles[i];
    const float x = static_cast<float>(v.x), y = static_cast<float>(v.y);
    out[0] = x;
    out[1] = y;
    out[2] = height;
    std::uint32_t vertex_colour = packed;
    if (i < alpha.size() && alpha[i] < 1.0f)
    {
      Ogre::ColourValue faded = colour;
      faded.a = colour.a * std::max(0.0f, alpha[i]);
      vertex_colour = Ogre::VertexElement::convertColourValue(faded, colour_type);
    }
    std::memcpy(out + 3, &vertex_colour, sizeof vertex_colour);
    out += 4;
    bounds.add(x, y, height);
  }
  renderable_->unlock(triangles.size(), bounds.box());
  triangle_count_ = triangles.size() / 3;
  if (!shown_)
  {
    renderable_->setVisible(false);
  }
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
  Bounds bounds;
  float* out = renderable_->lock(triangles.size(), FloorMeshRenderable::Layout::PositionNormal);
  for (const MeshVertex& v : triangles)
  {
    const float x = static_cast<float>(v.position.x), y = static_cast<float>(v.position.y),
                h = static_cast<float>(v.position.z + z);
    out[0] = x;
    out[1] = y;
    out[2] = h;
    out[3] = static_cast<float>(v.normal.x);
    out[4] = static_cast<float>(v.normal.y);
    out[5] = static_cast<float>(v.normal.z);
    out += 6;
    bounds.add(x, y, h);
  }
  renderable_->unlock(triangles.size(), bounds.box());
  triangle_count_ = triangles.size() / 3;
  if (!shown_)
  {
    renderable_->setVisible(false);
  }
}

void FloorMesh::setVisibilityFlags(std::uint32_t flags)
{
  renderable_->setVisibilityFlags(flags);
}

void FloorMesh::setLayer(std::uint16_t layer)
{
  // Render priorities within the main queue group: OGRE draws them in increasing order (each one's
  // opaque, then translucent objects), after the default priority's.
  renderable_->setRenderQueueGroupAndPriority(renderable_->getRenderQueueGroup(),
                                              static_cast<Ogre::ushort>(OGRE_RENDERABLE_DEFAULT_PRIORITY + layer));
}

void FloorMesh::setShown(bool shown)
{
  shown_ = shown;
  renderable_->setVisible(shown_ && triangle_count_ > 0);
}

void FloorMesh::clear()
{
  renderable_->clear();
  triangle_count_ = 0;
}

std::size_t FloorMesh::bufferAllocations() const
{
  return renderable_->allocations();
}
}  // namespace rviz_projector
