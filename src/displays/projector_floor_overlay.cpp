#include "rviz_projector/displays/projector_floor_overlay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <OgreColourValue.h>

#include "rviz_projector/core/floor_grid.h"
#include "rviz_projector/displays/floor_mesh.h"
#include "rviz_projector/displays/projector_footprint_visual.h"

namespace rviz_projector
{
namespace
{
/// Test-pattern extent around the lit area, metres, and its bound.
constexpr double kGridMargin = 0.5;
constexpr double kGridMaxHalfExtent = 25.0;
}  // namespace

std::string footprintStatusText(const FloorOverlayResult& result)
{
  if (!result.complete)
  {
    return "Part of the image does not reach the floor (projector aims at or above the horizon, or the floor is "
           "farther than 10 m)";
  }
  char text[1024];  // three %.2f of any double fit
  std::snprintf(text, sizeof(text), "Lit floor area %.2f x %.2f m, throw distance %.2f m", result.width, result.depth,
                result.throw_distance);
  return text;
}

ProjectorFloorOverlay::ProjectorFloorOverlay(Ogre::SceneManager* scene_manager, Ogre::SceneNode* parent)
  : footprint_(std::make_unique<ProjectorFootprintVisual>(scene_manager, parent))
  , grid_mesh_(std::make_unique<FloorMesh>(scene_manager, parent))
{
  footprint_->setVisible(false);
}

ProjectorFloorOverlay::~ProjectorFloorOverlay() = default;

void ProjectorFloorOverlay::setFootprintVisible(bool visible)
{
  footprint_->setVisible(visible);
}

void ProjectorFloorOverlay::setFootprintVisibilityFlags(std::uint32_t flags)
{
  footprint_->setVisibilityFlags(flags);
}

void ProjectorFloorOverlay::clearGrid()
{
  grid_mesh_->clear();
  grid_triangles_.clear();
}

FloorOverlayResult ProjectorFloorOverlay::update(const PinholeModel& lens, const LensDistortion& distortion,
                                                 const RigidTransform& optical_to_fixed, std::uint64_t revision,
                                                 bool footprint, bool grid)
{
  FloorOverlayResult result;
  std::array<double, 12> key{};
  std::copy(optical_to_fixed.rotation().begin(), optical_to_fixed.rotation().end(), key.begin());
  const Vec3& position = optical_to_fixed.translation();
  key[9] = position.x;
  key[10] = position.y;
  key[11] = position.z;
  if (key == key_ && revision == revision_)
  {
    return result;  // same pose, lens and settings: as drawn
  }
  key_ = key;
  revision_ = revision;
  result.recomputed = true;
  const FloorFootprint lit(lens, optical_to_fixed, kFrustumLength, distortion);
  result.complete = lit.complete();
  result.width = lit.width();
  result.depth = lit.depth();
  result.throw_distance = lit.throwDistance();
  // (An incomplete footprint's text has no figures; they may be infinite.)
  const std::array<long long, 4> status_key =
      result.complete ? std::array<long long, 4>{2, std::llround(result.width * 100.0), std::llround(result.depth * 100.0),
                                                 std::llround(result.throw_distance * 100.0)} :
                        std::array<long long, 4>{1, 0, 0, 0};
  result.status_changed = status_key != status_key_;
  status_key_ = status_key;
  if (footprint)
  {
    footprint_->update(lit);
  }
  if (!grid)
  {
    return result;
  }
  // The grid covers the lit area plus a margin, in whole metres (bounded), so its mesh is rebuilt
  // only when the lit area moves a lot.
  Vec2 lo{position.x - kGridMargin, position.y - kGridMargin};
  Vec2 hi{position.x + kGridMargin, position.y + kGridMargin};
  for (const Vec3& c : lit.corners())
  {
    lo = Vec2{std::min(lo.x, c.x - kGridMargin), std::min(lo.y, c.y - kGridMargin)};
    hi = Vec2{std::max(hi.x, c.x + kGridMargin), std::max(hi.y, c.y + kGridMargin)};
  }
  lo = Vec2{std::floor(std::max(std::floor(lo.x), position.x - kGridMaxHalfExtent)),
            std::floor(std::max(std::floor(lo.y), position.y - kGridMaxHalfExtent))};
  hi = Vec2{std::ceil(std::min(std::ceil(hi.x), position.x + kGridMaxHalfExtent)),
            std::ceil(std::min(std::ceil(hi.y), position.y + kGridMaxHalfExtent))};
  scratch_.clear();
  FloorGrid(lo, hi).appendTriangles(scratch_);
  if (scratch_.size() != grid_triangles_.size() ||
      (!scratch_.empty() && (scratch_.front().x != grid_triangles_.front().x ||
                             scratch_.front().y != grid_triangles_.front().y)))
  {
    grid_triangles_.swap(scratch_);
    grid_mesh_->setFlatTriangles(grid_triangles_, 0.0, Ogre::ColourValue::White);
    result.grid_changed = true;
  }
  return result;
}
}  // namespace rviz_projector
