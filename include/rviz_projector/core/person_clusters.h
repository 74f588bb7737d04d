// People for the Acknowledge cue of ProjectionMask (issue 25, part 4): the clusters of a laser
// scan's floor points that are person-sized. Plain geometry (no ROS, no OGRE).
#pragma once

#include <cstddef>
#include <vector>

#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
/// Which clusters count as people.
struct ClusterLimits
{
  double gap = 0.3;          ///< metres: consecutive points further apart than this start a new cluster
  double min_width = 0.05;   ///< metres: narrower clusters (a table leg, noise) are no person
  double max_width = 1.0;    ///< metres: wider clusters (a wall, a shelf) are no person
  std::size_t min_points = 3;  ///< clusters of fewer points are no person
};

/// A person-sized cluster.
struct PersonCluster
{
  Vec2 centre;              ///< the mean of its points
  double radius = 0.0;      ///< the largest distance from `centre` to one of its points
  std::size_t points = 0;   ///< how many points it has
};

/// What clustering did with its input.
struct ClusterCount
{
  std::size_t clusters = 0;   ///< clusters found (people or not)
  std::size_t people = 0;     ///< of them, person-sized (kept)
  std::size_t ignored = 0;    ///< non-finite points skipped
};

/**
 * Splits a scan's floor points, in the scan's order (scanToFloorPoints keeps it), into clusters:
 * a point starts a new cluster when it is more than `limits.gap` from the previous one (a
 * non-finite point is skipped and ends the cluster too). A cluster's width is the diameter of the
 * circle about its mean that holds all its points (2 x radius); clusters with min_width <= width
 * <= max_width and at least min_points points are people, appended to `people` (cleared first,
 * capacity kept). Limits that are NaN, negative, or a max below the min find nobody. The last and
 * first beams of a 360 degree scan are not joined (a person right behind the scanner may count as
 * two clusters). Point clouds are not clustered (the Acknowledge cue uses the scan only).
 */
ClusterCount findPersonClusters(const std::vector<Vec2>& points, const ClusterLimits& limits,
                                std::vector<PersonCluster>& people);
}  // namespace rviz_projector
