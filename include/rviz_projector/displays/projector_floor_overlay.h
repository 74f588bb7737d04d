// One part of ProjectorCameraDisplay: what it draws on the floor itself. In rviz's main view the
// projector's frustum and lit area (ProjectorFootprintVisual); in the projector view the metric test
// grid (Test pattern). Recomputed only when the projector's pose, lens or settings changed.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rviz_projector/core/floor_footprint.h"
#include "rviz_projector/core/lens_distortion.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/rigid_transform.h"
#include "rviz_projector/core/vec2.h"

namespace Ogre
{
class SceneManager;
class SceneNode;
}  // namespace Ogre

namespace rviz_projector
{
class FloorMesh;
class ProjectorFootprintVisual;

/// What update() found, for the "Footprint" status.
struct FloorOverlayResult
{
  bool recomputed = false;     ///< false: nothing changed since the last call, statuses stand
  bool complete = false;       ///< every corner ray hits the floor
  double width = 0.0;          ///< lit area across, metres
  double depth = 0.0;          ///< lit area along, metres
  double throw_distance = 0.0; ///< lens to the image centre on the floor, metres
  bool grid_changed = false;   ///< the test grid's mesh was rebuilt (the projector view must render)
  /// The Footprint status must be shown anew: completeness or a figure as the status shows it (to
  /// the centimetre) changed, or invalidate() was called. While the robot drives on a flat floor
  /// the figures stay: no status text is built per frame.
  bool status_changed = false;
};

/// The "Footprint" status text of a result: the lit area and throw distance (an Ok status) when
/// complete, otherwise why part of the image misses the floor (a warning).
std::string footprintStatusText(const FloorOverlayResult& result);

class ProjectorFloorOverlay
{
public:
  /// Rays that miss the floor are drawn to this distance in the main view, metres.
  static constexpr double kFrustumLength = 10.0;

  ProjectorFloorOverlay(Ogre::SceneManager* scene_manager, Ogre::SceneNode* parent);
  ~ProjectorFloorOverlay();

  /**
   * Follows the projector. `optical_to_fixed`: pose of its optical frame in the fixed frame (floor
   * at z = 0); `distortion` the lens's D (the outline follows it); `revision` changes whenever the
   * lens or a setting changed. Draws the footprint lines when `footprint`, the metric grid when
   * `grid`.
   */
  FloorOverlayResult update(const PinholeModel& lens, const LensDistortion& distortion,
                            const RigidTransform& optical_to_fixed, std::uint64_t revision, bool footprint, bool grid);
  /// Forces the next update() to recompute (fixed frame changed, statuses were reset).
  void invalidate()
  {
    revision_ = ~0ull;
    status_key_ = {};
  }
  void setFootprintVisible(bool visible);
  void clearGrid();
  /// Visibility flags of the footprint lines (the projector's own view must not see them).
  void setFootprintVisibilityFlags(std::uint32_t flags);

private:
  std::unique_ptr<ProjectorFootprintVisual> footprint_;
  std::unique_ptr<FloorMesh> grid_mesh_;
  std::array<double, 12> key_{};
  std::uint64_t revision_ = ~0ull;
  std::array<long long, 4> status_key_{};  ///< completeness (1/2) and the shown figures in cm; {} = none
  std::vector<Vec2> grid_triangles_;
  std::vector<Vec2> scratch_;
};
}  // namespace rviz_projector
