// One arrow lying on the floor plane: it points from tail to tip.
#pragma once

#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
struct Arrow
{
  Vec2 tail;
  Vec2 tip;
};
}  // namespace rviz_projector
