#include "rviz_projector/displays/projection_animation.h"

#include <algorithm>

namespace rviz_projector
{
std::vector<AnimatedDrawing*>& ProjectionAnimation::drawings()
{
  static std::vector<AnimatedDrawing*> all;
  return all;
}

void ProjectionAnimation::add(AnimatedDrawing* drawing)
{
  auto& all = drawings();
  if (drawing && std::find(all.begin(), all.end(), drawing) == all.end())
  {
    all.push_back(drawing);
  }
}

void ProjectionAnimation::remove(AnimatedDrawing* drawing)
{
  auto& all = drawings();
  all.erase(std::remove(all.begin(), all.end(), drawing), all.end());
}

void ProjectionAnimation::advanceAll(const ros::Time& now)
{
  auto& all = drawings();
  for (std::size_t i = 0; i < all.size(); ++i)  // by index: the contract forbids changes meanwhile
  {
    all[i]->advance(now);
  }
}
}  // namespace rviz_projector
