#include "rviz_projector/displays/floor_mesh_renderable.h"

#include <algorithm>
#include <cmath>

#include <OgreCamera.h>
#include <OgreHardwareBufferManager.h>
#include <OgreNode.h>
#include <OgreSceneNode.h>

namespace rviz_projector
{
namespace
{
constexpr std::size_t kMinCapacity = 1024;            // vertices; about a hundred arrows
constexpr std::size_t kShrinkAboveCapacity = 1 << 18;  // keep up to 256k vertices (6 MB) however few are used

std::size_t roundUpToPowerOfTwo(std::size_t n)
{
  std::size_t capacity = kMinCapacity;
  while (capacity < n)
  {
    capacity *= 2;
  }
  return capacity;
}
}  // namespace

FloorMeshRenderable::FloorMeshRenderable()
{
  mRenderOp.vertexData = new Ogre::VertexData();
  mRenderOp.vertexData->vertexStart = 0;
  mRenderOp.vertexData->vertexCount = 0;
  mRenderOp.operationType = Ogre::RenderOperation::OT_TRIANGLE_LIST;
  mRenderOp.useIndexes = false;
  setVisible(false);
  setCastShadows(false);
}

FloorMeshRenderable::~FloorMeshRenderable()
{
  delete mRenderOp.vertexData;  // also releases its binding of buffer_
}

void FloorMeshRenderable::allocate(std::size_t capacity, Layout layout)
{
  Ogre::VertexDeclaration* declaration = mRenderOp.vertexData->vertexDeclaration;
  declaration->removeAllElements();
  std::size_t offset = declaration->addElement(0, 0, Ogre::VET_FLOAT3, Ogre::VES_POSITION).getSize();
  if (layout == Layout::PositionColour)
  {
    declaration->addElement(0, offset, Ogre::VertexElement::getBestColourVertexElementType(), Ogre::VES_DIFFUSE);
  }
  else
  {
    declaration->addElement(0, offset, Ogre::VET_FLOAT3, Ogre::VES_NORMAL);
  }
  mRenderOp.vertexData->vertexBufferBinding->unsetAllBindings();
  buffer_ = Ogre::HardwareBufferManager::getSingleton().createVertexBuffer(
      declaration->getVertexSize(0), capacity, Ogre::HardwareBuffer::HBU_DYNAMIC_WRITE_ONLY_DISCARDABLE);
  mRenderOp.vertexData->vertexBufferBinding->setBinding(0, buffer_);
  capacity_ = capacity;
  layout_ = layout;
  ++allocations_;
}

float* FloorMeshRenderable::lock(std::size_t vertex_count, Layout layout)
{
  const bool too_small = vertex_count > capacity_;
  const bool far_too_large = capacity_ > kShrinkAboveCapacity && vertex_count < capacity_ / 8;
  if (buffer_.get() == nullptr || layout != layout_ || too_small || far_too_large)
  {
    allocate(roundUpToPowerOfTwo(vertex_count), layout);
  }
  const std::size_t bytes = std::max<std::size_t>(vertex_count, 1) * buffer_->getVertexSize();
  return static_cast<float*>(buffer_->lock(0, bytes, Ogre::HardwareBuffer::HBL_DISCARD));
}

void FloorMeshRenderable::unlock(std::size_t vertex_count, const Ogre::AxisAlignedBox& bounds)
{
  buffer_->unlock();
  mRenderOp.vertexData->vertexCount = vertex_count;
  const bool visible = vertex_count > 0 && !bounds.isNull();
  setBoundingBox(visible ? bounds : Ogre::AxisAlignedBox());
  radius_ = visible ? std::sqrt(std::max(bounds.getMinimum().squaredLength(), bounds.getMaximum().squaredLength())) : 0;
  setVisible(visible);
  if (mParentNode != nullptr)
  {
    mParentNode->needUpdate();  // the node's bounds include ours
  }
}

void FloorMeshRenderable::clear()
{
  mRenderOp.vertexData->vertexCount = 0;
  setBoundingBox(Ogre::AxisAlignedBox());
  radius_ = 0;
  setVisible(false);
  if (mParentNode != nullptr)
  {
    mParentNode->needUpdate();
  }
}

Ogre::Real FloorMeshRenderable::getSquaredViewDepth(const Ogre::Camera* camera) const
{
  // Depth of the mesh's centre, for sorting transparent meshes back to front.
  if (mBox.isNull())
  {
    return 0;
  }
  const Ogre::Vector3 centre = mParentNode != nullptr ? mParentNode->_getFullTransform() * mBox.getCenter() : mBox.getCenter();
  return (centre - camera->getDerivedPosition()).squaredLength();
}

Ogre::Real FloorMeshRenderable::getBoundingRadius() const
{
  return radius_;
}
}  // namespace rviz_projector
