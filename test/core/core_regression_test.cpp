// Regressions found by the fuzz targets in fuzz/ (and by the robustness matrix): each test is the
// smallest input that broke an invariant, written as the behaviour the core must have.
//
// A bug found and not fixed yet would be pinned by a DISABLED_ test (and an RP_FUZZ_SKIP_KNOWN_BUG
// in fuzz/); the ones found so far are fixed.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "rviz_projector/core/arrow_outline.h"
#include "rviz_projector/core/arrow_solid.h"
#include "rviz_projector/core/floor_footprint.h"
#include "rviz_projector/core/floor_grid.h"
#include "rviz_projector/core/off_view_cue.h"
#include "rviz_projector/core/path_spacer.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/swept_corridor.h"
#include "rviz_projector/core/path_location.h"

using namespace rviz_projector;

namespace
{
const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();
const double kDenormal = std::numeric_limits<double>::denorm_min();

bool allFinite(const std::vector<Vec2>& points)
{
  for (const Vec2& p : points)
  {
    if (!isFinite(p))
    {
      return false;
    }
  }
  return true;
}
}  // namespace

// Fixed bug 1 (found by fuzz_shapes): floor_grid.cpp lineRange() casts lo / cell and hi / cell to long
// unchecked; a grid far from the origin (a tf pose of 1e20 m reaches it through the projector's
// test pattern) is undefined behaviour (clang UBSan: "1.55899e+296 is outside the range of
// representable values of type 'long'"; gcc's -fsanitize=undefined does not check this). On
// x86 the cast gives LONG_MIN: one line at x = -9.2e17 m. Expected: such a grid draws nothing
// (or only lines within its rectangle).
TEST(CoreRegression, FloorGridFarFromTheOriginIsEmptyNotUndefined)
{
  const Vec2 min{1e20, 1e20}, max{1.000001e20, 1.000001e20};  // 1e14 m wide: distinct doubles
  const FloorGrid grid(min, max, 0.1);
  std::vector<Vec2> triangles;
  grid.appendTriangles(triangles);
  EXPECT_LE(grid.verticalLineCount(), FloorGrid::kMaxLines);
  EXPECT_TRUE(allFinite(triangles));
  for (const Vec2& v : triangles)
  {
    const bool origin_cross = std::fabs(v.x) <= FloorGrid::kOriginMark && std::fabs(v.y) <= FloorGrid::kOriginMark;
    ASSERT_TRUE(origin_cross || (v.x >= min.x && v.x <= max.x && v.y >= min.y && v.y <= max.y))
        << "vertex " << v.x << ", " << v.y << " outside the grid's rectangle";
  }
  const FloorGrid huge(Vec2{-1.5e296, -1.0}, Vec2{1.5e296, 1.0}, 0.1);
  triangles.clear();
  huge.appendTriangles(triangles);
  EXPECT_LE(huge.verticalLineCount(), FloorGrid::kMaxLines);
}

// Fixed bug 2 (found by fuzz_pinhole): pinhole_model.cpp checks fx, fy > 0 before the binning divides
// them; a tiny focal length binned by a large factor is accepted as exactly 0 and ray() divides
// by it. Crash input: K = {denorm_min, 0, -487.6, 0, denorm_min, -1779.7, 0, 0, 1}, P all zero,
// binning 1852730990 x 1852730990, 2864706413 x 2443764736 pixels.
TEST(CoreRegression, TinyFocalLengthIsRefusedBeforeAndAfterBinning)
{
  LensCalibration c;
  c.width = 2864706413u;
  c.height = 2443764736u;
  c.K = {kDenormal, 0, -487.60652449476743, 0, kDenormal, -1779.6782787592169, 0, 0, 1};
  c.binning_x = c.binning_y = 1852730990u;
  PinholeModel lens;
  const LensCheck check = PinholeModel::fromCalibration(c, lens);
  EXPECT_FALSE(check.ok()) << "accepted fx = " << lens.fx() << ", fy = " << lens.fy();
  // Without binning, a focal length of 1e-300 pixels is no lens either: its rays are infinite.
  LensCalibration tiny;
  tiny.width = 640;
  tiny.height = 480;
  tiny.K = {1e-300, 0, 320, 0, 1e-300, 240, 0, 0, 1};
  EXPECT_FALSE(PinholeModel::fromCalibration(tiny, lens).ok());
}

// Fixed bug 3 (found by fuzz_shapes): arrow_outline.cpp normalises the direction as along * (1 / length);
// for a denormal length the reciprocal is Inf and a valid() arrow gets NaN corners.
TEST(CoreRegression, ArrowOutlineOfADenormalLengthHasFiniteCorners)
{
  const ArrowOutline outline(Arrow{Vec2{0.0, 0.0}, Vec2{kDenormal, 0.0}}, ArrowDimensions());
  if (outline.valid())
  {
    for (const Vec2& c : outline.corners())
    {
      EXPECT_TRUE(isFinite(c)) << c.x << ", " << c.y;
    }
  }
}

// fuzz_shapes (CI of 28 Nov, then a local run): an arrow 7.3e-162 m long.
// - Sizes 2.2e-308 m: norm() squared the length into the denormal range, so its direction was 1.6 %
//   off unit length and so were the shaft's normals (0.984).
// - A head 0.3 m long (clipped to the arrow's length) and 0.28 m wide: the cone's slope r / l
//   overflowed and its normals came out zero.
TEST(CoreRegression, ArrowSolidNearTheBottomOfTheDoubleRangeHasUnitNormals)
{
  const double tiny = std::numeric_limits<double>::min();  // 2.2250738585072014e-308
  for (const double head_length : {tiny, 0.3})
  {
    ArrowDimensions d;
    d.shaft_length = d.shaft_diameter = tiny;
    d.head_length = head_length;
    d.head_diameter = head_length == tiny ? tiny : 0.27683823537602154;
    std::vector<MeshVertex> mesh;
    ArrowSolid(Arrow{Vec2{tiny, tiny}, Vec2{7.2566535644953999e-162, tiny}}, d).appendTriangles(mesh);
    ASSERT_EQ(mesh.size(), ArrowSolid::kVerticesPerArrow);
    for (const MeshVertex& v : mesh)
    {
      ASSERT_TRUE(isFinite(v.position) && isFinite(v.normal));
      EXPECT_NEAR(1.0, std::sqrt(v.normal.x * v.normal.x + v.normal.y * v.normal.y + v.normal.z * v.normal.z), 1e-6)
          << "head " << head_length << " m";
    }
  }
}

// Fixed behaviour worth keeping (each was a fuzz seed that passed, written down as a contract).
TEST(CoreRegression, ArrowSolidOfADenormalLengthHasFiniteUnitNormals)
{
  std::vector<MeshVertex> mesh;
  ArrowSolid(Arrow{Vec2{0.0, 0.0}, Vec2{kDenormal, 0.0}}, ArrowDimensions()).appendTriangles(mesh);
  for (const MeshVertex& v : mesh)
  {
    ASSERT_TRUE(isFinite(v.position) && isFinite(v.normal));
  }
}

TEST(CoreRegression, PathSpacerWithNonsenseParametersFallsBackToDefaults)
{
  SpacingParameters p;
  p.mode = static_cast<SpacingMode>(7);
  p.spacing = kNan;
  p.arrow.head_length = -kInf;
  p.circle_diameter = kInf;
  p.destination_gap = -1.0;
  const PathSpacer spacer(p);
  EXPECT_EQ(spacer.parameters().mode, SpacingMode::Exact);
  EXPECT_EQ(spacer.parameters().spacing, SpacingParameters().spacing);
  EXPECT_EQ(spacer.parameters().arrow.head_length, SpacingParameters().arrow.head_length);
  EXPECT_EQ(spacer.parameters().circle_diameter, SpacingParameters().circle_diameter);
  EXPECT_EQ(spacer.parameters().destination_gap, 0.0);
}

TEST(CoreRegression, BillionMetrePathStaysBoundedAndFinite)
{
  // 1e9 m of path at the smallest spacing: max_arrows bounds the work and the memory.
  SpacingParameters p;
  p.spacing = SpacingParameters::kMinSpacing;
  p.max_arrows = 1000;
  PathSpacer spacer(p);
  const SpacedPath& r = spacer.space({Vec2{-5e8, 1e9}, Vec2{5e8, 1e9}});
  EXPECT_EQ(r.arrows.size(), 1000u);
  EXPECT_TRUE(r.truncated);
  for (const Arrow& a : r.arrows)
  {
    ASSERT_TRUE(isFinite(a.tip) && isFinite(a.tail));
  }
}

TEST(CoreRegression, AllPointsIdenticalGiveADestinationAndNoArrows)
{
  for (SpacingMode mode : {SpacingMode::Exact, SpacingMode::Paper})
  {
    SpacingParameters p;
    p.mode = mode;
    PathSpacer spacer(p);
    const SpacedPath& r = spacer.space(std::vector<Vec2>(1000, Vec2{3.0, -2.0}));
    EXPECT_TRUE(r.has_destination);
    EXPECT_TRUE(r.arrows.empty());
    EXPECT_EQ(r.path_length, 0.0);
  }
}

TEST(CoreRegression, FootprintOfAZeroQuaternionPoseIsFinite)
{
  const PinholeModel lens(1280, 800, 1300, 1300, 639.5, 399.5);
  const FloorFootprint footprint(lens, RigidTransform::fromQuaternion(0, 0, 0, 0, Vec3{0, 0, 1.2}), 10.0);
  for (const Vec3& c : footprint.corners())
  {
    EXPECT_TRUE(isFinite(c));
  }
  const FloorFootprint nan_pose(lens, RigidTransform::fromQuaternion(kNan, 0, 0, 1, Vec3{0, 0, 1.2}), 10.0);
  EXPECT_TRUE(isFinite(nan_pose.origin()));
}

// fuzz_shapes (known-bug-2-corridor-parallel-edges): a footprint edge at two places, parallel,
// passed segmentsCross by rounding; its "crossing" was at infinity and Clipper threw "Coordinate
// outside allowed range", ending the process.
TEST(CoreRegression, CorridorEdgeParallelToItsNextPlaceDoesNotThrow)
{
  const std::vector<Vec2> points{{-0.0, -0.0}, {-0.0, -0.0}, {-0.0, -0.0}, {-0.0, -0.0}, {-0.0, -0.0}, {-0.0, -0.0},
                                 {-0.0, -0.0}, {-0.0, -0.0}, {20, 20}, {20, 20},
                                 {19.982352941176469, 19.982352941176469}, {19.964701574128668, 20.28235294117647},
                                 {20, -0.0}, {20, -0.0}, {20, -0.0}, {-0.0, 2.8177690084182086e-202},
                                 {-0.0, 2.8177690084182086e-202}, {-0.0, 2.8177690084182086e-202},
                                 {-0.0, 2.8177690084182086e-202}, {-0.0, 2.8177690084182086e-202},
                                 {-0.0, 2.8177690084182086e-202}, {0.29999999999999999, 0.29999999999999999}};
  const std::vector<Vec2> footprint{{1, 1}, {0.99586397058823528, -0.058823529411764719}, {-0.058823529411764719, 1}};
  std::vector<double> lengths;
  accumulateArcLengths(points, lengths);
  CorridorParameters parameters;
  parameters.length = 5.0;
  parameters.edge_width = 0.099997211531096836;
  SweptCorridor corridor;
  EXPECT_NO_THROW(corridor.build(points, lengths, 0.0, footprint, parameters));
  EXPECT_FALSE(corridor.band().empty());
  for (const Vec2& v : corridor.band())
  {
    EXPECT_TRUE(std::isfinite(v.x) && std::isfinite(v.y));
  }
}

// fuzz_shapes: a huge margin (1e300 m) made Clipper's offset leave its integer range and throw.
TEST(CoreRegression, OffViewCueWithAHugeMarginIsRefusedNotThrown)
{
  const std::vector<Vec2> points{{0, 0}, {0.2, 0}, {0.2, 2}};
  std::vector<double> lengths;
  accumulateArcLengths(points, lengths);
  OffViewInput input;
  input.lit = {{0.3, 0.4}, {1.3, 0.4}, {1.3, -0.4}, {0.3, -0.4}};
  OffViewParameters parameters;
  OffViewCue cue;
  for (const double margin : {1e300, 4e13, 0.4})
  {
    parameters.margin = margin;
    EXPECT_NO_THROW(cue.build(points, lengths, input, parameters));
    EXPECT_EQ(cue.result().reason, "lit area too small for the margin");
  }
}
