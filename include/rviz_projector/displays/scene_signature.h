// A hash of what a part of OGRE's scene graph looks like from outside: node transforms and the
// attached objects' visibility and bounds. projector_host uses it to see whether displays of other
// packages (which do not announce their changes to this package) moved or changed since the last
// projector frame. Content that changes inside unchanged bounds is not seen here: projector_host
// renders a keep-alive frame for it (RenderPolicy::keep_alive_s, render_policy.h).
#pragma once

#include <cstdint>

namespace Ogre
{
class SceneNode;
}

namespace rviz_projector
{
/// Mixes `node` and everything below it into `hash` (FNV-1a): each node's position, orientation,
/// scale and child count, each attached object's type, visibility, visibility flags and bounding
/// box. No allocation. A null node mixes a marker only.
void mixSceneSignature(const Ogre::SceneNode* node, std::uint64_t& hash);
}  // namespace rviz_projector
