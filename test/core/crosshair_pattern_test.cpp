// Crosshair pattern (issue 12): hand-computed centres, and what is drawn for each crosshair (inside
// the image, edges on pixel boundaries, a symmetric cross, readable distinct digits clear of it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "rviz_projector/core/crosshair_pattern.h"

using rviz_projector::Crosshair;
using rviz_projector::crosshairDrawing;
using rviz_projector::CrosshairDrawing;
using rviz_projector::crosshairPattern;
using rviz_projector::crosshairPatternProblem;
using rviz_projector::crosshairPatternRects;
using rviz_projector::PatternRect;

namespace
{
struct Expected
{
  int id;
  double u;
  double v;
};

void expectPattern(std::uint32_t w, std::uint32_t h, int rows, int cols, const std::vector<Expected>& expected)
{
  const std::vector<Crosshair> p = crosshairPattern(w, h, rows, cols);
  ASSERT_EQ(p.size(), expected.size()) << w << "x" << h << " " << rows << "x" << cols;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    EXPECT_EQ(p[i].id, expected[i].id) << "index " << i;
    EXPECT_EQ(p[i].pixel.x, expected[i].u) << "id " << expected[i].id;
    EXPECT_EQ(p[i].pixel.y, expected[i].v) << "id " << expected[i].id;
  }
}

bool onPixelEdge(double x)
{
  return std::fabs(x + 0.5 - std::round(x + 0.5)) < 1e-12;
}

/// Pixels (col, row) covered by the rectangles (their edges on pixel boundaries).
std::set<std::pair<int, int>> raster(const std::vector<PatternRect>& rects)
{
  std::set<std::pair<int, int>> out;
  for (const PatternRect& r : rects)
  {
    for (int c = static_cast<int>(std::lround(r.x0 + 0.5)); c < std::lround(r.x1 + 0.5); ++c)
    {
      for (int row = static_cast<int>(std::lround(r.y0 + 0.5)); row < std::lround(r.y1 + 0.5); ++row)
      {
        out.insert({c, row});
      }
    }
  }
  return out;
}

std::size_t pixelArea(const std::vector<PatternRect>& rects)
{
  std::size_t area = 0;
  for (const PatternRect& r : rects)
  {
    area += static_cast<std::size_t>(std::lround((r.x1 - r.x0) * (r.y1 - r.y0)));
  }
  return area;
}
}  // namespace

// Hand computation: column i of n at -0.5 + 0.1 W + i 0.8 W / (n - 1), ties rounded up.
TEST(CrosshairPattern, HandComputed3x3On1280x800)
{
  // u: 127.5, 639.5, 1151.5 -> 128, 640, 1152; v: 79.5, 399.5, 719.5 -> 80, 400, 720.
  expectPattern(1280, 800, 3, 3,
                {{1, 128, 80}, {2, 640, 80}, {3, 1152, 80}, {4, 128, 400}, {5, 640, 400}, {6, 1152, 400},
                 {7, 128, 720}, {8, 640, 720}, {9, 1152, 720}});
}

TEST(CrosshairPattern, HandComputedSingleCrosshair)
{
  expectPattern(1280, 800, 1, 1, {{1, 640, 400}});  // (1279 / 2, 799 / 2) = (639.5, 399.5), ties up
  expectPattern(1281, 801, 1, 1, {{1, 640, 400}});  // exactly the middle pixel
}

TEST(CrosshairPattern, HandComputed2x4And4x3)
{
  // 4 columns of 1280: 127.5, 468.83, 810.17, 1151.5; 2 rows of 800: 79.5, 719.5.
  expectPattern(1280, 800, 2, 4,
                {{1, 128, 80}, {2, 469, 80}, {3, 810, 80}, {4, 1152, 80}, {5, 128, 720}, {6, 469, 720},
                 {7, 810, 720}, {8, 1152, 720}});
  // 1366 x 768, 4 rows x 3 cols: u 136.1, 682.5, 1228.9; v 76.3, 281.1, 485.9, 690.7.
  expectPattern(1366, 768, 4, 3,
                {{1, 136, 76}, {2, 683, 76}, {3, 1229, 76}, {4, 136, 281}, {5, 683, 281}, {6, 1229, 281},
                 {7, 136, 486}, {8, 683, 486}, {9, 1229, 486}, {10, 136, 691}, {11, 683, 691}, {12, 1229, 691}});
}

TEST(CrosshairPattern, OutOfRangeGivesNothingAndSaysWhy)
{
  const std::vector<std::tuple<std::uint32_t, std::uint32_t, int, int>> bad = {
      {15, 800, 3, 3}, {1280, 15, 3, 3}, {0, 0, 3, 3}, {1280, 800, 0, 3}, {1280, 800, 3, 0},
      {1280, 800, 11, 3}, {1280, 800, 3, 11}, {1280, 800, -1, 3}, {16385, 800, 3, 3}};
  for (const auto& [w, h, rows, cols] : bad)
  {
    EXPECT_TRUE(crosshairPattern(w, h, rows, cols).empty()) << w << "x" << h << " " << rows << "x" << cols;
    EXPECT_FALSE(crosshairPatternProblem(w, h, rows, cols).empty());
  }
  EXPECT_EQ(crosshairPatternProblem(16, 16, 10, 10), "");
  EXPECT_EQ(crosshairPattern(16, 16, 10, 10).size(), 100u);
  EXPECT_EQ(crosshairPattern(1280, 800).size(), 9u);
}

TEST(CrosshairPattern, CentresAreWholePixelsInsideTheCentralPart)
{
  for (const auto& [w, h] : std::vector<std::pair<std::uint32_t, std::uint32_t>>{
           {1280, 800}, {1920, 1080}, {16, 16}, {17, 31}, {4096, 2160}, {801, 599}})
  {
    for (int rows = 1; rows <= 10; ++rows)
    {
      for (int cols = 1; cols <= 10; ++cols)
      {
        const std::vector<Crosshair> p = crosshairPattern(w, h, rows, cols);
        ASSERT_EQ(p.size(), static_cast<std::size_t>(rows * cols));
        for (const Crosshair& c : p)
        {
          EXPECT_EQ(c.pixel.x, std::round(c.pixel.x));
          EXPECT_EQ(c.pixel.y, std::round(c.pixel.y));
          EXPECT_GE(c.pixel.x, 0.1 * w - 0.5 - 0.5);
          EXPECT_LE(c.pixel.x, 0.9 * w - 0.5 + 0.5);
          EXPECT_GE(c.pixel.y, 0.1 * h - 0.5 - 0.5);
          EXPECT_LE(c.pixel.y, 0.9 * h - 0.5 + 0.5);
        }
      }
    }
  }
}

TEST(CrosshairPatternRects, EveryRectangleInsideTheImageOnPixelEdges)
{
  for (const auto& [w, h] : std::vector<std::pair<std::uint32_t, std::uint32_t>>{
           {1280, 800}, {1920, 1080}, {16, 16}, {17, 31}, {640, 480}, {801, 599}, {100, 3000}})
  {
    for (const auto& [rows, cols] : std::vector<std::pair<int, int>>{{1, 1}, {3, 3}, {2, 4}, {10, 10}})
    {
      const std::vector<PatternRect> rects = crosshairPatternRects(crosshairPattern(w, h, rows, cols), w, h);
      EXPECT_GE(rects.size(), static_cast<std::size_t>(rows * cols * 3));
      for (const PatternRect& r : rects)
      {
        EXPECT_LT(r.x0, r.x1);
        EXPECT_LT(r.y0, r.y1);
        EXPECT_GE(r.x0, -0.5);
        EXPECT_GE(r.y0, -0.5);
        EXPECT_LE(r.x1, w - 0.5);
        EXPECT_LE(r.y1, h - 0.5);
        EXPECT_TRUE(onPixelEdge(r.x0) && onPixelEdge(r.y0) && onPixelEdge(r.x1) && onPixelEdge(r.y1));
      }
    }
  }
  // Crosshairs right at the border: arms shortened, digits moved inward, still inside.
  for (const Crosshair& c : std::vector<Crosshair>{{7, {0, 0}}, {88, {1279, 799}}, {100, {1279, 0}}, {5, {0, 799}}})
  {
    const CrosshairDrawing d = crosshairDrawing(c, 1280, 800);
    EXPECT_FALSE(d.label.empty());
    for (const std::vector<PatternRect>* part : {&d.cross, &d.label})
    {
      for (const PatternRect& r : *part)
      {
        EXPECT_GE(r.x0, -0.5);
        EXPECT_GE(r.y0, -0.5);
        EXPECT_LE(r.x1, 1279.5);
        EXPECT_LE(r.y1, 799.5);
      }
    }
  }
}

TEST(CrosshairPatternRects, CrossIsSymmetricWithOddLinesAndSeparateFromTheDigits)
{
  for (const auto& [w, h] : std::vector<std::pair<std::uint32_t, std::uint32_t>>{
           {1280, 800}, {1920, 1080}, {3840, 2160}, {16, 16}, {640, 480}})
  {
    for (const Crosshair& c : crosshairPattern(w, h, 3, 3))
    {
      const CrosshairDrawing d = crosshairDrawing(c, w, h);
      const auto cross = raster(d.cross);
      EXPECT_EQ(cross.size(), pixelArea(d.cross)) << "cross rectangles overlap";
      const int u = static_cast<int>(c.pixel.x);
      const int v = static_cast<int>(c.pixel.y);
      ASSERT_TRUE(cross.count({u, v})) << "centre pixel not drawn";
      for (const auto& [col, row] : cross)
      {
        EXPECT_TRUE(cross.count({2 * u - col, row}) && cross.count({col, 2 * v - row}) &&
                    cross.count({u + (row - v), v + (col - u)}))  // mirror and 90-degree symmetric
            << "pixel " << col << "," << row << " of the cross around " << u << "," << v;
      }
      // Line width: the drawn pixels in the column of the right arm's last pixel.
      int end = u;
      while (cross.count({end + 1, v}))
      {
        ++end;
      }
      EXPECT_GE(end, u + 1) << "no right arm";
      int width = 0;
      for (const auto& p : cross)
      {
        width += p.first == end ? 1 : 0;
      }
      EXPECT_EQ(width % 2, 1) << w << "x" << h;
      // min side / 400 rounded, then up to odd: 800 -> 2 -> 3, 1080 -> 3, 2160 -> 5, 480 -> 1, 16 -> 1.
      const int expected_width = h == 2160 ? 5 : (h >= 800 ? 3 : 1);
      EXPECT_EQ(width, expected_width) << w << "x" << h;
      const auto label = raster(d.label);
      for (const auto& p : label)
      {
        EXPECT_FALSE(cross.count(p)) << "digit pixel on the cross";
      }
    }
  }
}

TEST(CrosshairPatternRects, SizesOn1280x800)
{
  // min side 800: line 800/400 = 2 -> odd 3; arm 40; digit height 800/12 = 66.7 -> 67.
  const CrosshairDrawing d = crosshairDrawing({5, {640, 400}}, 1280, 800);
  ASSERT_EQ(d.cross.size(), 3u);
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (const PatternRect& r : d.cross)
  {
    x0 = std::min(x0, r.x0), x1 = std::max(x1, r.x1), y0 = std::min(y0, r.y0), y1 = std::max(y1, r.y1);
  }
  EXPECT_EQ(x0, 640 - 1 - 40 - 0.5);
  EXPECT_EQ(x1, 640 + 1 + 40 + 0.5);
  EXPECT_EQ(y0, 400 - 1 - 40 - 0.5);
  EXPECT_EQ(y1, 400 + 1 + 40 + 0.5);
  double ly0 = 1e9, ly1 = -1e9, lx0 = 1e9;
  for (const PatternRect& r : d.label)
  {
    ly0 = std::min(ly0, r.y0), ly1 = std::max(ly1, r.y1), lx0 = std::min(lx0, r.x0);
  }
  EXPECT_EQ(ly1 - ly0, 67);  // a "5" has its top and bottom segments
  EXPECT_GT(ly0, 401.5);     // below the horizontal arm
  EXPECT_GT(lx0, 641.5);     // right of the vertical arm
}

TEST(CrosshairPatternRects, DigitsHaveTheirSegmentsAndAreDistinct)
{
  // Segments lit per digit on a seven-segment display, counted by hand.
  const int kSegments[10] = {6, 2, 5, 5, 4, 5, 6, 3, 7, 6};
  std::set<std::vector<std::tuple<double, double, double, double>>> shapes;
  for (int id = 1; id <= 100; ++id)
  {
    const CrosshairDrawing d = crosshairDrawing({id, {640, 400}}, 1280, 800);
    int expected = 0;
    for (int rest = id; rest > 0; rest /= 10)
    {
      expected += kSegments[rest % 10];
    }
    EXPECT_EQ(static_cast<int>(d.label.size()), expected) << "id " << id;
    std::vector<std::tuple<double, double, double, double>> shape;
    for (const PatternRect& r : d.label)
    {
      shape.emplace_back(r.x0, r.y0, r.x1, r.y1);
    }
    std::sort(shape.begin(), shape.end());
    EXPECT_TRUE(shapes.insert(shape).second) << "id " << id << " looks like another id";
  }
  // A "1" is two segments stacked in one column; "7" adds the top bar across the full digit width.
  const CrosshairDrawing one = crosshairDrawing({1, {640, 400}}, 1280, 800);
  ASSERT_EQ(one.label.size(), 2u);
  EXPECT_EQ(one.label[0].x0, one.label[1].x0);
  EXPECT_LT(one.label[0].y0, one.label[1].y0);
}
