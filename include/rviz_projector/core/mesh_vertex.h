#pragma once

#include "rviz_projector/core/vec3.h"

namespace rviz_projector
{
/// A vertex of a shaded mesh: position and unit normal, metres.
struct MeshVertex
{
  Vec3 position;
  Vec3 normal;
};
}  // namespace rviz_projector
