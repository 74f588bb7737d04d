// PathTriangles: what one spaced path hands to the meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "rviz_projector/core/arrow_outline.h"
#include "rviz_projector/core/arrow_solid.h"
#include "rviz_projector/core/disc_outline.h"
#include "rviz_projector/core/path_spacer.h"
#include "rviz_projector/core/path_triangles.h"

using rviz_projector::ArrowOutline;
using rviz_projector::ArrowSolid;
using rviz_projector::PathSpacer;
using rviz_projector::PathTriangles;
using rviz_projector::SpacedPath;
using rviz_projector::SpacingParameters;
using rviz_projector::Vec2;

TEST(PathTriangles, ArrowsInTheChosenStyleAndTheDestinationDisc)
{
  SpacingParameters p;
  p.circle_diameter = 0.4;
  PathSpacer spacer(p);
  const SpacedPath& spaced = spacer.space({{0.0, 0.0}, {5.0, 0.0}});
  ASSERT_GT(spaced.arrows.size(), 3u);
  PathTriangles triangles;

  triangles.build(spaced, spacer.parameters(), PathTriangles::ArrowStyle::Flat);
  ASSERT_EQ(triangles.flatArrows().size(), spaced.arrows.size() * ArrowOutline::kVerticesPerArrow);
  EXPECT_TRUE(triangles.solidArrows().empty());
  // Every flat vertex lies on its arrow's outline: first arrow's triangles start at its tail.
  const ArrowOutline first(spaced.arrows[0], spacer.parameters().arrow);
  EXPECT_EQ(triangles.flatArrows()[0].x, first.corners()[0].x);
  EXPECT_EQ(triangles.flatArrows()[0].y, first.corners()[0].y);
  // The disc: centred on the destination (5, 0), 0.2 m radius.
  ASSERT_FALSE(triangles.destination().empty());
  double farthest = 0.0;
  for (const Vec2& v : triangles.destination())
  {
    farthest = std::max(farthest, rviz_projector::distance(v, Vec2{5.0, 0.0}));
  }
  EXPECT_NEAR(farthest, 0.2, 1e-9);

  triangles.build(spaced, spacer.parameters(), PathTriangles::ArrowStyle::Solid);
  EXPECT_EQ(triangles.solidArrows().size(), spaced.arrows.size() * ArrowSolid::kVerticesPerArrow);
  EXPECT_TRUE(triangles.flatArrows().empty()) << "the other style's buffer is emptied";

  const SpacedPath& empty = spacer.space({});
  triangles.build(empty, spacer.parameters(), PathTriangles::ArrowStyle::Flat);
  EXPECT_TRUE(triangles.flatArrows().empty());
  EXPECT_TRUE(triangles.destination().empty());
}

TEST(PathTriangles, SolidArrowsAreCappedNearestTheDestinationFlatOnesAreNot)
{
  SpacedPath many;
  many.has_destination = true;
  for (std::size_t i = 0; i < PathTriangles::kMaxSolidArrows + 5; ++i)
  {
    const double x = -0.3 * static_cast<double>(i);  // arrow 0 nearest the destination at x = 0
    many.arrows.push_back({{x - 0.2, 0.0}, {x - 0.02, 0.0}});
  }
  const SpacingParameters p;
  PathTriangles triangles;
  triangles.build(many, p, PathTriangles::ArrowStyle::Solid);
  EXPECT_EQ(triangles.arrowsLeftOut(), 5u);
  ASSERT_EQ(triangles.solidArrows().size(), PathTriangles::kMaxSolidArrows * ArrowSolid::kVerticesPerArrow);
  // The last arrow drawn is arrow kMaxSolidArrows - 1: none of its vertices is beyond its tail.
  double min_x = 0.0;
  for (const auto& v : triangles.solidArrows())
  {
    min_x = std::min(min_x, v.position.x);
  }
  EXPECT_NEAR(min_x, many.arrows[PathTriangles::kMaxSolidArrows - 1].tail.x, 1e-9);

  triangles.build(many, p, PathTriangles::ArrowStyle::Flat);
  EXPECT_EQ(triangles.arrowsLeftOut(), 0u);
  EXPECT_EQ(triangles.flatArrows().size(), many.arrows.size() * ArrowOutline::kVerticesPerArrow);
}

TEST(PathTriangles, TheUnusedStylesBufferIsGivenBack)
{
  SpacedPath path;
  path.has_destination = true;
  for (int i = 0; i < 3000; ++i)
  {
    const double x = -0.3 * i;
    path.arrows.push_back({{x - 0.2, 0.0}, {x - 0.02, 0.0}});
  }
  const SpacingParameters p;
  PathTriangles triangles;
  triangles.build(path, p, PathTriangles::ArrowStyle::Solid);
  EXPECT_EQ(triangles.arrowsDrawn(), 3000u);
  EXPECT_GE(triangles.solidArrows().capacity(), 3000u * ArrowSolid::kVerticesPerArrow);
  triangles.build(path, p, PathTriangles::ArrowStyle::Flat);  // back to Flat: the 3D buffer goes
  EXPECT_EQ(triangles.solidArrows().capacity(), 0u);
  EXPECT_EQ(triangles.arrowsDrawn(), 3000u);
  triangles.build(path, p, PathTriangles::ArrowStyle::Solid);
  EXPECT_EQ(triangles.flatArrows().capacity(), 0u);
}

TEST(PathTriangles, InvalidArrowsAreNotCountedAsDrawn)
{
  SpacedPath path;
  path.has_destination = true;
  path.arrows.push_back({{-1.0, 0.0}, {-0.8, 0.0}});
  path.arrows.push_back({{-0.5, 0.0}, {-0.5, 0.0}});  // zero length: no direction, not drawable
  path.arrows.push_back({{-0.3, 0.0}, {-0.1, 0.0}});
  const SpacingParameters p;
  PathTriangles triangles;
  triangles.build(path, p, PathTriangles::ArrowStyle::Flat);
  EXPECT_EQ(triangles.arrowsDrawn(), 2u);
  triangles.build(path, p, PathTriangles::ArrowStyle::Solid);
  EXPECT_EQ(triangles.arrowsDrawn(), 2u);
}
