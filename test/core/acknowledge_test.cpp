// The Acknowledge cue of ProjectionMask (issue 25, part 4): person clusters, the tracker's
// association and fading, and the arc's triangles, against values computed by hand (a cluster's
// mean and radius; distances walked between scans; the annulus's radii, its middle direction
// towards the robot, and the side of a line by the sign of a cross product).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include "rviz_projector/core/acknowledge_arc.h"
#include "rviz_projector/core/person_clusters.h"
#include "rviz_projector/core/person_tracker.h"

using namespace rviz_projector;

namespace
{
constexpr double kPi = 3.14159265358979323846;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

double crossOf(const Vec2& a, const Vec2& b, const Vec2& c)
{
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/// Points from `a` to `b` (both included), `n` of them.
void line(std::vector<Vec2>& points, const Vec2& a, const Vec2& b, int n)
{
  for (int i = 0; i < n; ++i)
  {
    const double t = n == 1 ? 0.0 : double(i) / (n - 1);
    points.push_back({a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t});
  }
}

std::vector<PersonCluster> person(double x, double y)
{
  return {PersonCluster{{x, y}, 0.15, 10}};
}
}  // namespace

// --- clusters --------------------------------------------------------------------------------

TEST(PersonClusters, KeepsPersonSizedClustersAndDropsWallsAndSpecks)
{
  std::vector<Vec2> points;
  line(points, {1.0, 0.0}, {1.0, 0.2}, 5);    // a person: 0.2 m across, 5 points
  line(points, {3.0, 0.0}, {3.0, 2.0}, 41);   // a wall: 2 m
  line(points, {1.5, 3.0}, {1.5, 3.01}, 2);   // a speck of 2 points
  std::vector<PersonCluster> people;
  const ClusterCount count = findPersonClusters(points, ClusterLimits(), people);
  EXPECT_EQ(count.clusters, 3u);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_NEAR(people[0].centre.x, 1.0, 1e-12);
  EXPECT_NEAR(people[0].centre.y, 0.1, 1e-12);  // the mean of 0, 0.05 .. 0.2
  EXPECT_NEAR(people[0].radius, 0.1, 1e-12);
  EXPECT_EQ(people[0].points, 5u);
}

TEST(PersonClusters, GapSplitsAndNaNEndsACluster)
{
  ClusterLimits limits;
  limits.gap = 0.3;
  limits.min_points = 2;
  limits.min_width = 0.0;
  std::vector<Vec2> points{{0.0, 0.0}, {0.0, 0.29}, {0.0, 0.6}, {0.0, 0.7}};  // 0.31 between the 2nd and 3rd
  std::vector<PersonCluster> people;
  EXPECT_EQ(findPersonClusters(points, limits, people).clusters, 2u);
  ASSERT_EQ(people.size(), 2u);
  EXPECT_NEAR(people[0].centre.y, 0.145, 1e-12);
  EXPECT_NEAR(people[1].centre.y, 0.65, 1e-12);
  points = {{0.0, 0.0}, {0.0, 0.1}, {kNaN, 0.0}, {0.0, 0.2}, {0.0, 0.3}};
  const ClusterCount count = findPersonClusters(points, limits, people);
  EXPECT_EQ(count.ignored, 1u);
  EXPECT_EQ(people.size(), 2u);
  limits.max_width = -1.0;  // unusable: nobody
  EXPECT_EQ(findPersonClusters(points, limits, people).people, 0u);
  EXPECT_TRUE(people.empty());
}

TEST(PersonClusters, WidthLimitsAreInclusive)
{
  ClusterLimits limits;
  limits.min_width = 0.2;
  limits.max_width = 0.4;
  limits.min_points = 3;
  std::vector<PersonCluster> people;
  std::vector<Vec2> points;
  line(points, {0.0, 0.0}, {0.0, 0.19}, 3);  // 0.19 wide: too narrow
  line(points, {5.0, 0.0}, {5.0, 0.3}, 4);   // 0.3
  line(points, {9.0, 0.0}, {9.0, 0.41}, 5);  // 0.41: too wide
  findPersonClusters(points, limits, people);
  ASSERT_EQ(people.size(), 1u);
  EXPECT_NEAR(people[0].centre.x, 5.0, 1e-12);
}

// --- tracker ---------------------------------------------------------------------------------

TEST(PersonTracker, TwoPeopleWalkingPastEachOtherKeepTheirIds)
{
  // A walks +x at 1.4 m/s on y = 0, B walks -x on y = 0.4; 10 Hz scans. They pass 0.4 m apart.
  PersonTracker tracker;
  TrackerParameters params;
  std::map<std::uint32_t, double> y_of_id;
  for (int k = 0; k <= 30; ++k)
  {
    const double t = 0.1 * k;
    std::vector<PersonCluster> clusters{PersonCluster{{0.0 + 1.4 * t, 0.0}, 0.15, 8},
                                        PersonCluster{{4.2 - 1.4 * t, 0.4}, 0.15, 8}};
    if (k % 2)
    {
      std::swap(clusters[0], clusters[1]);  // the scan's order says nothing
    }
    tracker.update(clusters, t, params);
    ASSERT_EQ(tracker.tracks().size(), 2u) << "at " << t;
    for (const PersonTrack& track : tracker.tracks())
    {
      if (k == 0)
      {
        y_of_id[track.id] = track.position.y;
      }
      EXPECT_EQ(track.position.y, y_of_id.at(track.id)) << "ids swapped at t = " << t;
    }
  }
}

TEST(PersonTracker, PathsCrossingInAnXKeepTheirIds)
{
  // A from (0, 0) towards (4, 2), B from (0, 2) towards (4, 0), both 1.2 m/s, B 0.5 s later: they
  // cross the X's centre (2, 1) 0.5 s (0.6 m) apart.
  PersonTracker tracker;
  TrackerParameters params;
  const double s = 1.2 / std::sqrt(20.0);  // per unit of (4, 2)
  std::map<std::uint32_t, int> who;
  for (int k = 0; k <= 40; ++k)
  {
    const double t = 0.1 * k;
    const Vec2 a{4.0 * s * t, 2.0 * s * t};
    const double tb = std::max(0.0, t - 0.5);
    const Vec2 b{4.0 * s * tb, 2.0 - 2.0 * s * tb};
    tracker.update({PersonCluster{a, 0.15, 8}, PersonCluster{b, 0.15, 8}}, t, params);
    ASSERT_EQ(tracker.tracks().size(), 2u);
    for (const PersonTrack& track : tracker.tracks())
    {
      const int which = distance(track.position, a) < 1e-12 ? 0 : 1;
      if (k == 0)
      {
        who[track.id] = which;
      }
      EXPECT_EQ(which, who.at(track.id)) << "ids swapped at t = " << t;
    }
  }
}

TEST(PersonTracker, GateDropsATeleport)
{
  PersonTracker tracker;
  TrackerParameters params;  // 2.5 m/s, margin 0.2: after 0.1 s the gate is 0.45 m
  tracker.update(person(0.0, 0.0), 0.0, params);
  const std::uint32_t first = tracker.tracks().at(0).id;
  tracker.update(person(0.44, 0.0), 0.1, params);
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_EQ(tracker.tracks()[0].id, first) << "0.44 m in 0.1 s: within the gate";
  tracker.update(person(0.44 + 0.46, 0.0), 0.2, params);
  ASSERT_EQ(tracker.tracks().size(), 2u) << "0.46 m in 0.1 s: beyond the gate, a new person";
  for (const PersonTrack& track : tracker.tracks())
  {
    EXPECT_EQ(track.seen, track.id != first);
  }
  EXPECT_TRUE(tracker.fading());
}

TEST(PersonTracker, HoldAndFade)
{
  PersonTracker tracker;
  TrackerParameters params;
  params.hold = 2.0;
  tracker.update(person(1.0, 1.0), 10.0, params);
  EXPECT_DOUBLE_EQ(PersonTracker::opacity(tracker.tracks().at(0), 10.7, params), 1.0) << "seen: no fade";
  tracker.update({}, 10.1, params);  // gone from the scan
  ASSERT_EQ(tracker.tracks().size(), 1u);
  const PersonTrack track = tracker.tracks()[0];
  EXPECT_NEAR(PersonTracker::opacity(track, 10.5, params), 0.75, 1e-12);  // 1 - 0.5 / 2
  EXPECT_NEAR(PersonTracker::opacity(track, 11.0, params), 0.5, 1e-12);
  EXPECT_NEAR(PersonTracker::opacity(track, 12.0, params), 0.0, 1e-12);
  EXPECT_FALSE(tracker.expire(11.99, params));
  EXPECT_EQ(tracker.tracks().size(), 1u);
  EXPECT_TRUE(tracker.expire(12.01, params)) << "dropped Hold after it was last seen";
  EXPECT_TRUE(tracker.tracks().empty());
  params.hold = 0.0;
  EXPECT_DOUBLE_EQ(PersonTracker::opacity(track, 10.0, params), 0.0);
}

TEST(PersonTracker, BackwardTimeForgetsEveryone)
{
  PersonTracker tracker;
  TrackerParameters params;
  tracker.update(person(1.0, 1.0), 10.0, params);
  const std::uint32_t first = tracker.tracks().at(0).id;
  tracker.update(person(1.0, 1.0), 5.0, params);
  ASSERT_EQ(tracker.tracks().size(), 1u);
  EXPECT_NE(tracker.tracks()[0].id, first);
  tracker.update(person(1.0, 1.0), kNaN, params);
  EXPECT_TRUE(tracker.tracks().empty());
  tracker.update({PersonCluster{{kNaN, 0.0}, 0.1, 5}}, 6.0, params);
  EXPECT_TRUE(tracker.tracks().empty());
}

// --- arc -------------------------------------------------------------------------------------

namespace
{
AcknowledgeParameters arcParams()
{
  AcknowledgeParameters p;
  p.range = 1.5;
  p.distance = 0.3;
  p.arc_angle = 2.0 * kPi / 3.0;
  p.line_width = 0.05;
  return p;
}
const std::vector<Vec2> kPathX{{0.0, 0.0}, {2.0, 0.0}, {4.0, 0.0}};
}  // namespace

TEST(AcknowledgeArc, VerticesOnTheRadiiAndCentredTowardsTheRobot)
{
  // Person at (2, 1), feet 0.2: inner radius 0.5, outer 0.55. Robot at (0, 1): straight -x of them.
  std::vector<Vec2> tri;
  const AcknowledgeResult r = acknowledgeArc({2.0, 1.0}, 0.2, {0.0, 1.0}, {{0.0, 1.0}, {4.0, 1.0}}, arcParams(), tri);
  ASSERT_TRUE(r.drawn) << r.reason;
  ASSERT_FALSE(tri.empty());
  ASSERT_EQ(tri.size() % 3, 0u);
  double min_angle = 10.0, max_angle = -10.0;
  Vec2 sum;
  for (const Vec2& v : tri)
  {
    const double d = distance(v, {2.0, 1.0});
    EXPECT_TRUE(std::abs(d - 0.5) < 1e-9 || std::abs(d - 0.55) < 1e-9) << d;
    // angle from the direction to the robot (-x): atan2 of (-dy, -dx) mirrored
    const double a = std::atan2(-(v.y - 1.0), -(v.x - 2.0));
    min_angle = std::min(min_angle, a);
    max_angle = std::max(max_angle, a);
    sum = sum + v;
  }
  EXPECT_NEAR(min_angle, -kPi / 3.0, 1e-9);
  EXPECT_NEAR(max_angle, kPi / 3.0, 1e-9);
  // The distinct vertices (each is used by up to 3 triangles) are symmetric about the line to the robot.
  std::vector<std::pair<long, long>> distinct;
  for (const Vec2& v : tri)
  {
    distinct.push_back({std::lround(v.x * 1e8), std::lround(v.y * 1e8)});
  }
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  double mean_y = 0.0;
  for (const auto& v : distinct)
  {
    mean_y += v.second * 1e-8 / distinct.size();
  }
  EXPECT_NEAR(mean_y, 1.0, 1e-7) << "symmetric about the line to the robot";
  const Vec2 mean = sum * (1.0 / tri.size());
  EXPECT_LT(mean.x, 2.0 - 0.25) << "on the robot's side";
  for (std::size_t i = 0; i < tri.size(); i += 3)
  {
    EXPECT_GT(crossOf(tri[i], tri[i + 1], tri[i + 2]), 0.0) << "counter-clockwise from above";
  }
  EXPECT_EQ(r.side, 0) << "the person stands on the path";
  EXPECT_NEAR(r.path_distance, 0.0, 1e-12);
}

TEST(AcknowledgeArc, RobotBehindAtAnAngle)
{
  // Robot at (0, 0), person at (3, 4) (feet 0): the arc's middle points to (-0.6, -0.8).
  std::vector<Vec2> tri;
  AcknowledgeParameters p = arcParams();
  p.range = 10.0;
  p.arc_angle = 0.2;
  ASSERT_TRUE(acknowledgeArc({3.0, 4.0}, 0.0, {0.0, 0.0}, {{0.0, 0.0}, {3.0, 3.0}}, p, tri).drawn);
  for (const Vec2& v : tri)
  {
    const Vec2 d = v - Vec2{3.0, 4.0};
    EXPECT_GT(dot(d, {-0.6, -0.8}) / norm(d), std::cos(0.1) - 1e-9);
  }
}

TEST(AcknowledgeArc, RangeIsJudgedOnThePathAhead)
{
  std::vector<Vec2> tri;
  EXPECT_TRUE(acknowledgeArc({2.0, 1.4}, 0.1, {0.0, 0.0}, kPathX, arcParams(), tri).drawn);
  tri.clear();
  AcknowledgeResult r = acknowledgeArc({2.0, 1.6}, 0.1, {0.0, 0.0}, kPathX, arcParams(), tri);
  EXPECT_FALSE(r.drawn);
  EXPECT_NEAR(r.path_distance, 1.6, 1e-12);
  EXPECT_TRUE(tri.empty());
  // 0.5 m beside the part already driven, but 2.06 m from the part ahead (robot at x = 3).
  r = acknowledgeArc({1.0, 0.5}, 0.1, {3.0, 0.1}, kPathX, arcParams(), tri);
  EXPECT_FALSE(r.drawn);
  EXPECT_NEAR(r.path_distance, std::hypot(2.0, 0.5), 1e-12);
  EXPECT_EQ(r.reason, "out of Range of the path ahead");
  EXPECT_TRUE(tri.empty());
}

TEST(AcknowledgeArc, SideArrowIsOnThePathsSideAndPointsAlongIt)
{
  AcknowledgeParameters p = arcParams();
  p.side_arrow = true;
  struct Case
  {
    Vec2 person;
    std::vector<Vec2> path;
    Vec2 robot;
    int side;
    double tip_direction;  // +1: the arrow points +x
  };
  const std::vector<Case> cases{
      {{2.0, 0.8}, kPathX, {0.0, 0.0}, +1, +1.0},                                  // left of a +x path
      {{2.0, -0.8}, kPathX, {0.0, 0.0}, -1, +1.0},                                 // right of it
      {{2.0, 0.8}, {{4.0, 0.0}, {2.0, 0.0}, {0.0, 0.0}}, {4.0, 0.0}, -1, -1.0},    // a -x path: right of it
  };
  for (const Case& c : cases)
  {
    std::vector<Vec2> arc_only, tri;
    AcknowledgeParameters plain = p;
    plain.side_arrow = false;
    acknowledgeArc(c.person, 0.2, c.robot, c.path, plain, arc_only);
    const AcknowledgeResult r = acknowledgeArc(c.person, 0.2, c.robot, c.path, p, tri);
    ASSERT_TRUE(r.drawn);
    EXPECT_EQ(r.side, c.side);
    ASSERT_GT(tri.size(), arc_only.size());
    // The arrow's vertices: all between the person and the path (y between 0 and the person's y).
    double tip_x = c.tip_direction > 0 ? -1e9 : 1e9;
    for (std::size_t i = arc_only.size(); i < tri.size(); ++i)
    {
      const Vec2& v = tri[i];
      EXPECT_LT(std::abs(v.y), std::abs(c.person.y)) << "on the path's side of the person";
      EXPECT_GT(v.y * c.person.y, 0.0) << "not across the path";
      EXPECT_GE(distance(v, c.person), r.outer_radius - 1e-9) << "never nearer than the arc";
      tip_x = c.tip_direction > 0 ? std::max(tip_x, v.x) : std::min(tip_x, v.x);
    }
    for (std::size_t i = 0; i < tri.size(); i += 3)
    {
      EXPECT_GT(crossOf(tri[i], tri[i + 1], tri[i + 2]), 0.0);
    }
    // The tip is half the arrow's length (0.15 m) past the person's x, in the path's direction.
    EXPECT_NEAR(tip_x, c.person.x + c.tip_direction * 0.5 * kSideArrowLength, 1e-9);
  }
}

TEST(AcknowledgeArc, NeverOnTheFeet)
{
  // Every vertex at least feet_radius + distance from the person's centre, arrow included.
  AcknowledgeParameters p = arcParams();
  p.side_arrow = true;
  p.distance = 0.0;
  p.arc_angle = 2.0 * kPi;
  std::vector<Vec2> tri;
  ASSERT_TRUE(acknowledgeArc({1.0, 0.5}, 0.3, {0.0, 0.0}, kPathX, p, tri).drawn);
  for (const Vec2& v : tri)
  {
    EXPECT_GE(distance(v, {1.0, 0.5}), 0.3 - 1e-9);
  }
}

TEST(AcknowledgeArc, BadInputDrawsNothingAndSaysWhy)
{
  const AcknowledgeParameters p = arcParams();
  std::vector<Vec2> tri;
  const auto refused = [&](const AcknowledgeResult& r) { return !r.drawn && !r.reason.empty() && tri.empty(); };
  EXPECT_TRUE(refused(acknowledgeArc({kNaN, 0.0}, 0.1, {0.0, 0.0}, kPathX, p, tri)));
  EXPECT_TRUE(refused(acknowledgeArc({1.0, 0.0}, kNaN, {0.0, 0.0}, kPathX, p, tri)));
  EXPECT_TRUE(refused(acknowledgeArc({1.0, 0.0}, 0.1, {0.0, kNaN}, kPathX, p, tri)));
  EXPECT_TRUE(refused(acknowledgeArc({1.0, 0.5}, 0.1, {0.0, 0.0}, {}, p, tri)));
  EXPECT_TRUE(refused(acknowledgeArc({1.0, 0.5}, 0.1, {0.0, 0.0}, {{0.0, 0.0}, {kNaN, 1.0}}, p, tri)));
  EXPECT_TRUE(refused(acknowledgeArc({1e9, 0.5}, 0.1, {0.0, 0.0}, kPathX, p, tri)));
  EXPECT_TRUE(refused(acknowledgeArc({1.0, 0.5}, 0.1, {0.0, 0.0}, {{0.0, 0.0}, {1e300, 0.0}}, p, tri)));
  EXPECT_TRUE(refused(acknowledgeArc({1.0, 0.5}, 0.1, {1.0, 0.5}, kPathX, p, tri))) << "robot on the person";
  AcknowledgeParameters bad = p;
  bad.line_width = 0.0;
  EXPECT_TRUE(refused(acknowledgeArc({1.0, 0.5}, 0.1, {0.0, 0.0}, kPathX, bad, tri)));
  bad = p;
  bad.arc_angle = kNaN;
  EXPECT_TRUE(refused(acknowledgeArc({1.0, 0.5}, 0.1, {0.0, 0.0}, kPathX, bad, tri)));
  // A single-point path: the distance to that point; no side (no direction).
  const AcknowledgeResult one = acknowledgeArc({1.0, 0.5}, 0.1, {0.0, 0.0}, {{1.0, 0.0}}, p, tri);
  EXPECT_TRUE(one.drawn);
  EXPECT_NEAR(one.path_distance, 0.5, 1e-12);
  EXPECT_EQ(one.side, 0);
}
