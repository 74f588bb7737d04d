// FloorGrid: the metric test pattern.
#include <gtest/gtest.h>

#include <vector>

#include "rviz_projector/core/floor_grid.h"

using rviz_projector::FloorGrid;
using rviz_projector::Vec2;

TEST(FloorGrid, LinesEveryCellBoldEveryMetre)
{
  const FloorGrid grid({0.0, 0.0}, {1.0, 0.5}, 0.1);
  EXPECT_EQ(grid.verticalLineCount(), 11);  // x = 0, 0.1, ..., 1.0
  std::vector<Vec2> tris;
  grid.appendTriangles(tris);
  // 11 vertical + 6 horizontal lines, two crossing origin bars, each a rectangle of 6 vertices.
  ASSERT_EQ(tris.size(), (11u + 6u + 2u) * 6u);
  // The first line (x = 0) is a metre line: 12 mm wide; the second (x = 0.1) a 4 mm cell line.
  EXPECT_NEAR(tris[1].x - tris[0].x, FloorGrid::kMetreLineWidth, 1e-12);
  EXPECT_NEAR(tris[7].x - tris[6].x, FloorGrid::kCellLineWidth, 1e-12);
  EXPECT_NEAR(tris[6].x, 0.1 - FloorGrid::kCellLineWidth / 2, 1e-12);
}

TEST(FloorGrid, BadExtentsDrawNothingAndHugeOnesAreBounded)
{
  std::vector<Vec2> tris;
  FloorGrid({1.0, 1.0}, {0.0, 0.0}).appendTriangles(tris);
  EXPECT_TRUE(tris.empty());
  const FloorGrid huge({-1e6, -1.0}, {1e6, 1.0}, 0.1);
  EXPECT_EQ(huge.verticalLineCount(), FloorGrid::kMaxLines);
}
