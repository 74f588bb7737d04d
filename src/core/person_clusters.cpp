#include "rviz_projector/core/person_clusters.h"

#include <algorithm>
#include <cmath>

namespace rviz_projector
{
namespace
{
bool usable(const ClusterLimits& l)
{
  return std::isfinite(l.gap) && l.gap >= 0.0 && std::isfinite(l.min_width) && l.min_width >= 0.0 &&
         std::isfinite(l.max_width) && l.max_width >= l.min_width;
}

/// Judges points[begin, end) as one cluster; appends it to `people` when person-sized.
void judge(const std::vector<Vec2>& points, std::size_t begin, std::size_t end, const ClusterLimits& limits,
           ClusterCount& count, std::vector<PersonCluster>& people)
{
  if (end <= begin)
  {
    return;
  }
  ++count.clusters;
  Vec2 sum;
  for (std::size_t i = begin; i < end; ++i)
  {
    sum = sum + points[i];
  }
  const std::size_t n = end - begin;
  const Vec2 centre = sum * (1.0 / static_cast<double>(n));
  double radius = 0.0;
  for (std::size_t i = begin; i < end; ++i)
  {
    radius = std::max(radius, distance(centre, points[i]));
  }
  const double width = 2.0 * radius;
  if (n >= limits.min_points && width >= limits.min_width && width <= limits.max_width)
  {
    people.push_back(PersonCluster{centre, radius, n});
    ++count.people;
  }
}
}  // namespace

ClusterCount findPersonClusters(const std::vector<Vec2>& points, const ClusterLimits& limits,
                                std::vector<PersonCluster>& people)
{
  people.clear();
  ClusterCount count;
  if (!usable(limits))
  {
    return count;
  }
  std::size_t begin = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (!isFinite(points[i]))
    {
      judge(points, begin, i, limits, count, people);
      ++count.ignored;
      begin = i + 1;
      continue;
    }
    if (i > begin && !(distance(points[i - 1], points[i]) <= limits.gap))
    {
      judge(points, begin, i, limits, count, people);
      begin = i;
    }
  }
  judge(points, begin, points.size(), limits, count, people);
  return count;
}
}  // namespace rviz_projector
