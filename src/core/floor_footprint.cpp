#include "rviz_projector/core/floor_footprint.h"

#include <cmath>
#include <vector>

namespace rviz_projector
{
namespace
{
/// Distance along a unit ray to the plane z = 0, or a negative value when it does not get there.
double floorHitDistance(const Vec3& origin, const Vec3& direction)
{
  if (!(direction.z < 0.0) || !(origin.z > 0.0))
  {
    return -1.0;
  }
  return origin.z / -direction.z;
}
}  // namespace

FloorFootprint::FloorFootprint(const PinholeModel& lens, const RigidTransform& optical_to_world, double max_distance,
                               const LensDistortion& distortion)
{
  origin_ = optical_to_world.apply(lens.centre());
  const double w = lens.width();
  const double h = lens.height();
  // Outer edges of the corner pixels (pixel centres are at integers), clockwise from top-left.
  const std::array<Vec2, 4> image_corners{Vec2{-0.5, -0.5}, Vec2{w - 0.5, -0.5}, Vec2{w - 0.5, h - 0.5},
                                          Vec2{-0.5, h - 0.5}};
  // The outline's pixels, then their rays: the distorted normalised coordinates of the pixel,
  // undistorted (for a pinhole, the pixel's ray as it is).
  std::vector<Vec2> normalised;
  normalised.reserve(outline_.size() + 1);
  for (std::size_t i = 0; i < 4; ++i)
  {
    const Vec2& a = image_corners[i];
    const Vec2& b = image_corners[(i + 1) % 4];
    for (int k = 0; k < kEdgePoints; ++k)
    {
      const double s = double(k) / kEdgePoints;
      const Vec3 r = lens.ray({a.x + s * (b.x - a.x), a.y + s * (b.y - a.y)});
      normalised.push_back({r.x, r.y});
    }
  }
  const Vec3 centre = lens.ray(Vec2{0.5 * (w - 1.0), 0.5 * (h - 1.0)});
  normalised.push_back({centre.x, centre.y});
  const std::vector<Vec2> rays = distortion.undistort(normalised);

  complete_ = true;
  for (std::size_t i = 0; i < outline_.size(); ++i)
  {
    Vec3 d = optical_to_world.rotate(Vec3{rays[i].x, rays[i].y, 1.0});
    d = d * (1.0 / norm(d));
    double t = floorHitDistance(origin_, d);
    if (t < 0.0 || t > max_distance)
    {
      complete_ = false;
      t = max_distance;
    }
    outline_[i] = origin_ + d * t;
  }
  for (std::size_t i = 0; i < 4; ++i)
  {
    corners_[i] = outline_[i * kEdgePoints];
  }
  auto length = [](const Vec3& a, const Vec3& b) { return norm(a - b); };
  width_ = 0.5 * (length(corners_[0], corners_[1]) + length(corners_[3], corners_[2]));
  depth_ = 0.5 * (length(corners_[0], corners_[3]) + length(corners_[1], corners_[2]));

  Vec3 centre_ray = optical_to_world.rotate(Vec3{rays.back().x, rays.back().y, 1.0});
  centre_ray = centre_ray * (1.0 / norm(centre_ray));
  throw_distance_ = floorHitDistance(origin_, centre_ray);
}
}  // namespace rviz_projector
