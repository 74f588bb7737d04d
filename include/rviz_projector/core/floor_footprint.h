// Where a projector's image lands on the floor plane (z = 0 of the world frame).
#pragma once

#include <array>

#include "rviz_projector/core/lens_distortion.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/rigid_transform.h"
#include "rviz_projector/core/vec3.h"

namespace rviz_projector
{
class FloorFootprint
{
public:
  /**
   * @param optical_to_world pose of the projector's optical frame in the world (floor at z = 0)
   * @param max_distance rays that miss the floor, or hit it farther than this, end at this distance
   * @param distortion the lens's D (issue 24): a pixel's ray is the undistorted direction of that
   *        pixel, so the lit area's edges are curves (the outline follows them)
   */
  FloorFootprint(const PinholeModel& lens, const RigidTransform& optical_to_world, double max_distance,
                 const LensDistortion& distortion = LensDistortion());

  /// Points per image edge in outline() (corner to corner, the next corner not included).
  static constexpr int kEdgePoints = 8;

  /// Lens centre in the world.
  const Vec3& origin() const { return origin_; }
  /// Ends of the rays through the image's outer corners: top-left, top-right, bottom-right,
  /// bottom-left; on the floor where the ray hits it within max_distance.
  const std::array<Vec3, 4>& corners() const { return corners_; }
  /// Ends of the rays through the image's outer edge, clockwise from the top-left corner, kEdgePoints
  /// per edge (corners() among them): the lit area's outline (curved through a distorting lens).
  const std::array<Vec3, 4 * kEdgePoints>& outline() const { return outline_; }
  /// True when all outline rays hit the floor: the lit area is the polygon outline().
  bool complete() const { return complete_; }
  /// Mean length of the footprint's top and bottom edges (across the image), metres.
  double width() const { return width_; }
  /// Mean length of its left and right edges (along the image's vertical), metres.
  double depth() const { return depth_; }
  /// Distance from the lens to where the image centre's ray hits the floor; < 0 when it misses.
  double throwDistance() const { return throw_distance_; }

private:
  Vec3 origin_;
  std::array<Vec3, 4> corners_{};
  std::array<Vec3, 4 * kEdgePoints> outline_{};
  bool complete_ = false;
  double width_ = 0.0;
  double depth_ = 0.0;
  double throw_distance_ = -1.0;
};
}  // namespace rviz_projector
