#include "rviz_projector/core/path_triangles.h"

#include "rviz_projector/core/arrow_outline.h"
#include "rviz_projector/core/arrow_solid.h"
#include "rviz_projector/core/disc_outline.h"

namespace rviz_projector
{
void PathTriangles::build(const SpacedPath& path, const SpacingParameters& parameters, ArrowStyle style)
{
  if (style == ArrowStyle::Solid)
  {
    ArrowSolid::trianglesOf(path.arrows, parameters.arrow, solid_arrows_, kMaxSolidArrows);
    arrows_left_out_ = path.arrows.size() > kMaxSolidArrows ? path.arrows.size() - kMaxSolidArrows : 0;
    std::vector<Vec2>().swap(flat_arrows_);  // the other style's buffer is not kept
  }
  else
  {
    ArrowOutline::trianglesOf(path.arrows, parameters.arrow, flat_arrows_);
    arrows_left_out_ = 0;
    // Not kept while unused: 10,000 solid arrows take ~60 MB (~115 MB of capacity after growth).
    std::vector<MeshVertex>().swap(solid_arrows_);
  }
  destination_.clear();
  if (path.has_destination)
  {
    DiscOutline(path.destination, parameters.circle_diameter).appendTriangles(destination_);
  }
}

std::size_t PathTriangles::arrowsDrawn() const
{
  return flat_arrows_.size() / ArrowOutline::kVerticesPerArrow + solid_arrows_.size() / ArrowSolid::kVerticesPerArrow;
}
}  // namespace rviz_projector
