#include "rviz_projector/displays/scene_signature.h"

#include <cstring>

#include "rviz_projector/core/fnv_hash.h"

#include <OgreMovableObject.h>
#include <OgreSceneNode.h>

namespace rviz_projector
{
namespace
{
void mixBytes(std::uint64_t& hash, const void* data, std::size_t size)
{
  fnv1aMix(hash, data, size);
}

void mixValue(std::uint64_t& hash, std::uint64_t value)
{
  fnv1aMix(hash, value);
}

void mixFloats(std::uint64_t& hash, const float* values, std::size_t count)
{
  mixBytes(hash, values, count * sizeof(float));
}
}  // namespace

void mixSceneSignature(const Ogre::SceneNode* node, std::uint64_t& hash)
{
  if (node == nullptr)
  {
    mixValue(hash, 0x5ce7e5u);
    return;
  }
  const Ogre::Vector3& position = node->getPosition();
  const Ogre::Quaternion& orientation = node->getOrientation();
  const Ogre::Vector3& scale = node->getScale();
  const float transform[10] = {position.x,    position.y,    position.z, orientation.w, orientation.x,
                               orientation.y, orientation.z, scale.x,    scale.y,       scale.z};
  mixFloats(hash, transform, 10);
  const Ogre::SceneNode::ObjectMap& objects = node->getAttachedObjects();
  const Ogre::Node::ChildNodeMap& children = node->getChildren();
  mixValue(hash, objects.size());
  mixValue(hash, children.size());
  for (const Ogre::MovableObject* object : objects)
  {
    mixValue(hash, reinterpret_cast<std::uintptr_t>(object));
    mixValue(hash, (object->getVisible() ? 1u : 0u) | (static_cast<std::uint64_t>(object->getVisibilityFlags()) << 1));
    const Ogre::AxisAlignedBox& box = object->getBoundingBox();
    mixValue(hash, box.isNull() ? 0u : (box.isInfinite() ? 2u : 1u));
    if (box.isFinite())
    {
      const Ogre::Vector3& lo = box.getMinimum();
      const Ogre::Vector3& hi = box.getMaximum();
      const float bounds[6] = {lo.x, lo.y, lo.z, hi.x, hi.y, hi.z};
      mixFloats(hash, bounds, 6);
    }
  }
  for (const Ogre::Node* child : children)
  {
    mixSceneSignature(static_cast<const Ogre::SceneNode*>(child), hash);
  }
}
}  // namespace rviz_projector
