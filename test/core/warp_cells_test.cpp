// WarpCellScan and chooseWarpCells (issue 24: the warp on a software renderer draws only the cells
// with something on them). The oracle: each cell's two triangles sampled densely here, each sample
// interpolated as the GPU does (affine in the triangle) and read bilinearly (the texel at or before
// it and the next, clamped to the image), written independently of warp_cells.cpp. A cell that reads
// a lit texel must be drawn; a picture with nothing on it draws no cell.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <unordered_map>
#include <vector>

#include "rviz_projector/core/lens_distortion.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/unorm8.h"
#include "rviz_projector/core/warp_cells.h"
#include "rviz_projector/core/warp_grid.h"

using rviz_projector::LensDistortion;
using rviz_projector::PinholeModel;
using rviz_projector::Vec2;
using rviz_projector::WarpCells;
using rviz_projector::WarpCellScan;
using rviz_projector::WarpGrid;

namespace
{
const PinholeModel kLens(1280, 800, 1900.0, 1900.0, 639.5, 399.5);

WarpGrid wideGrid()
{
  return rviz_projector::makeWarpGrid(kLens, LensDistortion(LensDistortion::Model::PlumbBob, {-0.2, 0.05, 0, 0, 0}));
}

/// The cells that read each texel (x + y * width): each cell's two triangles sampled 25 x 25 times
/// (a sample every half texel or closer on the warp's 40 px cells), each sample read bilinearly.
std::unordered_map<std::uint32_t, std::vector<std::size_t>> cellsReading(const WarpGrid& g)
{
  const int w = int(g.ideal_lens.width());
  const int h = int(g.ideal_lens.height());
  std::unordered_map<std::uint32_t, std::vector<std::size_t>> readers;
  std::vector<std::uint32_t> read;
  for (std::uint32_t j = 0; j < g.rows; ++j)
  {
    for (std::uint32_t i = 0; i < g.columns; ++i)
    {
      const Vec2 a = g.ideal[j * (g.columns + 1) + i];
      const Vec2 b = g.ideal[j * (g.columns + 1) + i + 1];
      const Vec2 c = g.ideal[(j + 1) * (g.columns + 1) + i];
      const Vec2 d = g.ideal[(j + 1) * (g.columns + 1) + i + 1];
      read.clear();
      constexpr int n = 24;
      for (const auto& tri : {std::vector<Vec2>{a, b, c}, std::vector<Vec2>{b, d, c}})
      {
        for (int s = 0; s <= n; ++s)
        {
          for (int t = 0; s + t <= n; ++t)
          {
            const double u = double(s) / n, v = double(t) / n;
            const double px = tri[0].x + u * (tri[1].x - tri[0].x) + v * (tri[2].x - tri[0].x);
            const double py = tri[0].y + u * (tri[1].y - tri[0].y) + v * (tri[2].y - tri[0].y);
            const int x0 = int(std::floor(px)), y0 = int(std::floor(py));
            for (int dy = 0; dy <= 1; ++dy)
            {
              for (int dx = 0; dx <= 1; ++dx)
              {
                const int x = std::min(std::max(x0 + dx, 0), w - 1);
                const int y = std::min(std::max(y0 + dy, 0), h - 1);
                read.push_back(std::uint32_t(x + y * w));
              }
            }
          }
        }
      }
      std::sort(read.begin(), read.end());
      read.erase(std::unique(read.begin(), read.end()), read.end());
      for (const std::uint32_t texel : read)
      {
        readers[texel].push_back(std::size_t(j) * g.columns + i);
      }
    }
  }
  return readers;
}

/// The cells that read `texel` (none: an empty list).
const std::vector<std::size_t>& readersOf(const std::unordered_map<std::uint32_t, std::vector<std::size_t>>& oracle,
                                          std::uint32_t texel)
{
  static const std::vector<std::size_t> none;
  const auto it = oracle.find(texel);
  return it == oracle.end() ? none : it->second;
}
}  // namespace

TEST(WarpCellScan, APictureOfBackgroundOnlyDrawsNoCellWhateverItsAlpha)
{
  const WarpGrid g = wideGrid();
  WarpCellScan scan(g);
  const std::uint32_t w = g.ideal_lens.width(), h = g.ideal_lens.height();
  std::vector<std::uint8_t> occupied;
  // Black, and a grey background with random alpha (alpha is not shown: masked out).
  std::vector<std::uint32_t> picture(std::size_t(w) * h, 0u);
  EXPECT_EQ(scan.scan(picture.data(), w, h, w, 0u, 0x00FFFFFFu, occupied), 0u);
  ASSERT_EQ(occupied.size(), std::size_t(g.columns) * g.rows);
  EXPECT_EQ(std::count(occupied.begin(), occupied.end(), 0), int(occupied.size()));
  std::mt19937 rng(3);
  for (std::uint32_t& p : picture)
  {
    p = 0x00404040u | (std::uint32_t(rng() & 0xFFu) << 24);
  }
  EXPECT_EQ(scan.scan(picture.data(), w, h, w, 0xFF404040u, 0x00FFFFFFu, occupied), 0u);
  // The same grey against a black background: every cell.
  EXPECT_EQ(scan.scan(picture.data(), w, h, w, 0u, 0x00FFFFFFu, occupied), occupied.size());
}

TEST(WarpCellScan, EveryCellThatReadsALitTexelIsDrawnAndFewOthers)
{
  // A cell reads ~40 texels across and one before / two after it (bilinear, margin), so cells whose
  // reads overlap an 8-texel block start within 52 texels of each other: at most 2 x 2 cells.
  const std::size_t most_cells = 4;
  const WarpGrid g = wideGrid();
  const auto oracle = cellsReading(g);
  WarpCellScan scan(g);
  const std::uint32_t w = g.ideal_lens.width(), h = g.ideal_lens.height();
  // Padded rows: the padding is lit and must not count.
  const std::size_t stride = w + 7;
  std::vector<std::uint32_t> picture(stride * h, 0u);
  for (std::uint32_t y = 0; y < h; ++y)
  {
    std::fill(picture.begin() + std::ptrdiff_t(y * stride + w), picture.begin() + std::ptrdiff_t((y + 1) * stride),
              0xFFFFFFFFu);
  }
  std::vector<std::uint8_t> occupied;
  ASSERT_EQ(scan.scan(picture.data(), w, h, stride, 0u, 0x00FFFFFFu, occupied), 0u) << "padding counted";

  // Texels: the four corners, the texels around every vertex of the grid (cell edges), random ones.
  std::vector<std::pair<int, int>> texels{{0, 0}, {int(w) - 1, 0}, {0, int(h) - 1}, {int(w) - 1, int(h) - 1}};
  for (const Vec2& p : g.ideal)
  {
    for (const int d : {-1, 1})  // either side of the vertex: the texels of two or four cells
    {
      texels.emplace_back(std::min(std::max(int(std::floor(p.x)) + d, 0), int(w) - 1),
                          std::min(std::max(int(std::floor(p.y)) + d, 0), int(h) - 1));
    }
  }
  std::mt19937 rng(7);
  for (int k = 0; k < 300; ++k)
  {
    texels.emplace_back(int(rng() % w), int(rng() % h));
  }
  std::size_t most = 0;
  int checked = 0;
  for (const auto& t : texels)
  {
    const std::size_t at = std::size_t(t.second) * stride + std::size_t(t.first);
    picture[at] = 0x0000FF00u;  // green: a colour channel differs
    const std::size_t count = scan.scan(picture.data(), w, h, stride, 0u, 0x00FFFFFFu, occupied);
    picture[at] = 0u;
    const std::uint32_t index = std::uint32_t(t.first) + std::uint32_t(t.second) * w;
    const std::vector<std::size_t>& readers = readersOf(oracle, index);
    for (const std::size_t c : readers)
    {
      EXPECT_TRUE(occupied[c]) << "cell " << c << " reads texel (" << t.first << ", " << t.second
                               << ") but is not drawn";
    }
    EXPECT_GE(count, readers.size());
    most = std::max(most, count);
    ++checked;
  }
  EXPECT_GT(checked, 1500);
  EXPECT_LE(most, most_cells) << "a single lit texel drew " << most << " cells";
  EXPECT_GE(most, 1u);
}

TEST(WarpCellScan, APictureOfAnotherSizeDrawsEveryCell)
{
  const WarpGrid g = wideGrid();
  WarpCellScan scan(g);
  std::vector<std::uint32_t> picture(100 * 100, 0u);
  std::vector<std::uint8_t> occupied;
  EXPECT_EQ(scan.scan(picture.data(), 100, 100, 100, 0u, 0x00FFFFFFu, occupied), std::size_t(g.columns) * g.rows);
  EXPECT_EQ(scan.scan(nullptr, g.ideal_lens.width(), g.ideal_lens.height(), g.ideal_lens.width(), 0u, ~0u, occupied),
            std::size_t(g.columns) * g.rows);
}

TEST(WarpCellScan, FootprintsStayInsideTheImageAndCoverEachCellsCorners)
{
  const WarpGrid g = wideGrid();
  const std::vector<rviz_projector::CellFootprint> cells = rviz_projector::cellFootprints(g);
  ASSERT_EQ(cells.size(), std::size_t(g.columns) * g.rows);
  for (std::uint32_t j = 0; j < g.rows; ++j)
  {
    for (std::uint32_t i = 0; i < g.columns; ++i)
    {
      const rviz_projector::CellFootprint& f = cells[j * g.columns + i];
      EXPECT_LT(f.x0, f.x1);
      EXPECT_LT(f.y0, f.y1);
      EXPECT_LE(f.x1, g.ideal_lens.width());
      EXPECT_LE(f.y1, g.ideal_lens.height());
      const Vec2& corner = g.ideal[j * (g.columns + 1) + i];
      EXPECT_LE(double(f.x0), std::max(0.0, std::floor(corner.x)));
      EXPECT_LE(double(f.y0), std::max(0.0, std::floor(corner.y)));
    }
  }
}

TEST(ChooseWarpCells, SoftwareRenderersSkipEmptyCellsGpusDrawThemAllAndTheSettingWins)
{
  std::string error;
  EXPECT_EQ(rviz_projector::chooseWarpCells("", "llvmpipe (LLVM 15.0.6, 256 bits)", &error), WarpCells::Occupied);
  EXPECT_EQ(rviz_projector::chooseWarpCells("", "softpipe", &error), WarpCells::Occupied);
  EXPECT_EQ(rviz_projector::chooseWarpCells("auto", "Software Rasterizer", &error), WarpCells::Occupied);
  EXPECT_EQ(rviz_projector::chooseWarpCells("", "Mesa Intel(R) UHD Graphics 620 (KBL GT2)", &error), WarpCells::All);
  EXPECT_EQ(rviz_projector::chooseWarpCells("", "NVIDIA GeForce RTX 3060/PCIe/SSE2", &error), WarpCells::All);
  EXPECT_EQ(rviz_projector::chooseWarpCells("", "", &error), WarpCells::All);
  EXPECT_TRUE(error.empty()) << error;
  EXPECT_EQ(rviz_projector::chooseWarpCells("all", "llvmpipe", &error), WarpCells::All);
  EXPECT_EQ(rviz_projector::chooseWarpCells("OCCUPIED", "NVIDIA GeForce", &error), WarpCells::Occupied);
  EXPECT_TRUE(error.empty()) << error;
  EXPECT_EQ(rviz_projector::chooseWarpCells("sparse", "llvmpipe", &error), WarpCells::Occupied);
  EXPECT_NE(error.find("'sparse'"), std::string::npos) << error;
}

// The picture in strips of rows (texture_rows.h reads the ideal render back that way): every strip
// size finds the cells that read a lit texel (the cellsReading oracle) and the same cells as the
// whole picture at once.
TEST(WarpCellScan, StripsOfAnySizeFindTheCellsOfTheWholePicture)
{
  const WarpGrid g = wideGrid();
  const auto oracle = cellsReading(g);
  WarpCellScan scan(g);
  const std::uint32_t w = g.ideal_lens.width(), h = g.ideal_lens.height();
  const std::size_t stride = w + 3;  // padded rows, the padding lit: must not count
  std::vector<std::uint32_t> picture(stride * h, 0xFF000000u);
  for (std::uint32_t y = 0; y < h; ++y)
  {
    std::fill(picture.begin() + std::ptrdiff_t(y * stride + w), picture.begin() + std::ptrdiff_t((y + 1) * stride),
              0xFFFFFFFFu);
  }
  std::mt19937 rng(11);
  std::vector<std::uint32_t> lit;
  for (int k = 0; k < 40; ++k)
  {
    const std::uint32_t x = rng() % w, y = rng() % h;
    picture[std::size_t(y) * stride + x] = 0xFF0000FFu;  // one colour channel
    lit.push_back(x + y * w);
  }
  // The last column and row: the narrower last block, the last strip.
  picture[std::size_t(h - 1) * stride + (w - 1)] = 0xFF00FF00u;
  lit.push_back((w - 1) + (h - 1) * w);
  std::vector<std::uint8_t> whole;
  const std::size_t whole_count = scan.scan(picture.data(), w, h, stride, 0xFF000000u, 0x00FFFFFFu, whole);
  for (const std::uint32_t t : lit)
  {
    for (const std::size_t c : readersOf(oracle, t))
    {
      EXPECT_TRUE(whole[c]) << "cell " << c << " reads lit texel " << t;
    }
  }
  ASSERT_GT(whole_count, 0u);
  ASSERT_LT(whole_count, whole.size());
  for (const std::uint32_t rows : {1u, 7u, 16u, 17u, 64u, 100u, h - 1, h})
  {
    std::vector<std::uint8_t> strips;
    scan.begin(0xFF000000u, 0x00FFFFFFu);
    for (std::uint32_t y = 0; y < h; y += rows)
    {
      scan.addRows(picture.data() + std::size_t(y) * stride, y, std::min(rows, h - y), stride);
    }
    EXPECT_EQ(scan.finish(strips), whole_count) << rows << "-row strips";
    EXPECT_EQ(strips, whole) << rows << "-row strips";
  }
}

// Rows missing, repeated, out of order or narrower than the picture: never a cell dropped (every
// cell drawn); the next picture is scanned afresh.
TEST(WarpCellScan, StripsThatAreNotThePictureDrawEveryCell)
{
  const WarpGrid g = wideGrid();
  WarpCellScan scan(g);
  const std::uint32_t w = g.ideal_lens.width(), h = g.ideal_lens.height();
  const std::size_t all = std::size_t(g.columns) * g.rows;
  const std::vector<std::uint32_t> dark(std::size_t(w) * h, 0u);
  std::vector<std::uint8_t> occupied;
  auto rowsAt = [&](std::uint32_t y) { return dark.data() + std::size_t(y) * w; };

  scan.begin(0u, 0x00FFFFFFu);  // the last rows never come
  scan.addRows(rowsAt(0), 0, h - 1, w);
  EXPECT_EQ(scan.finish(occupied), all) << "a row missing";

  scan.begin(0u, 0x00FFFFFFu);  // a gap
  scan.addRows(rowsAt(0), 0, 64, w);
  scan.addRows(rowsAt(128), 128, h - 128, w);
  EXPECT_EQ(scan.finish(occupied), all) << "rows 64-127 missing";

  scan.begin(0u, 0x00FFFFFFu);  // a strip again
  scan.addRows(rowsAt(0), 0, 64, w);
  scan.addRows(rowsAt(0), 0, h, w);
  EXPECT_EQ(scan.finish(occupied), all) << "rows given twice";

  scan.begin(0u, 0x00FFFFFFu);  // past the end
  scan.addRows(rowsAt(0), 0, h, w);
  scan.addRows(rowsAt(0), h, 1, w);
  EXPECT_EQ(scan.finish(occupied), all) << "a row beyond the picture";

  scan.begin(0u, 0x00FFFFFFu);  // rows narrower than the picture
  scan.addRows(rowsAt(0), 0, h, w - 1);
  EXPECT_EQ(scan.finish(occupied), all) << "a stride shorter than the picture's width";

  scan.begin(0u, 0x00FFFFFFu);
  scan.addRows(nullptr, 0, h, w);
  EXPECT_EQ(scan.finish(occupied), all) << "no rows";

  scan.begin(0u, 0x00FFFFFFu);  // afresh: the dark picture draws nothing
  scan.addRows(rowsAt(0), 0, h, w);
  EXPECT_EQ(scan.finish(occupied), 0u);
  EXPECT_EQ(occupied.size(), all);
}

// litRects (the eraser paints them back to the background next frame, warp_eraser.h): every pixel
// that is not background lies in a rectangle; every rectangle pixel lies in an 8x8 block (counted
// here from the pixels) that holds such a pixel; rectangles do not overlap and stay in the picture.
TEST(WarpCellScan, LitRectsCoverEveryLitPixelAndOnlyTheirBlocks)
{
  const WarpGrid g = wideGrid();
  WarpCellScan scan(g);
  const std::uint32_t w = g.ideal_lens.width(), h = g.ideal_lens.height();
  constexpr std::uint32_t kB = 8;  // the block edge, as the scan's documentation gives it
  ASSERT_EQ(WarpCellScan::kBlock, kB);
  std::vector<std::uint32_t> picture(std::size_t(w) * h, 0xFF000000u);
  auto lit = [&](std::uint32_t x, std::uint32_t y) { picture[std::size_t(y) * w + x] = 0xFF00FF00u; };
  std::mt19937 rng(17);
  for (int k = 0; k < 60; ++k)  // dots
  {
    lit(rng() % w, rng() % h);
  }
  for (std::uint32_t y = 40; y < 240; ++y)  // a bar on block edges: one tall rectangle
  {
    for (std::uint32_t x = 800; x < 816; ++x)
    {
      lit(x, y);
    }
  }
  for (std::uint32_t y = 0; y < h; ++y)  // a disc crossing blocks, and the last column and row
  {
    for (std::uint32_t x = 0; x < w; ++x)
    {
      if (std::hypot(double(x) - 500.3, double(y) - 420.7) < 37.0 || x == w - 1 || y == h - 1)
      {
        lit(x, y);
      }
    }
  }
  std::vector<std::uint8_t> occupied;
  scan.scan(picture.data(), w, h, w, 0xFF000000u, 0x00FFFFFFu, occupied);
  ASSERT_TRUE(scan.complete());
  std::vector<rviz_projector::TexelRect> rects;
  scan.litRects(rects);
  // The oracle's blocks: any pixel in it not background.
  const std::uint32_t bw = (w + kB - 1) / kB, bh = (h + kB - 1) / kB;
  std::vector<std::uint8_t> block(std::size_t(bw) * bh, 0);
  for (std::uint32_t y = 0; y < h; ++y)
  {
    for (std::uint32_t x = 0; x < w; ++x)
    {
      if ((picture[std::size_t(y) * w + x] & 0x00FFFFFFu) != 0u)
      {
        block[std::size_t(y / kB) * bw + x / kB] = 1;
      }
    }
  }
  EXPECT_EQ(scan.litBlocks(), std::size_t(std::count(block.begin(), block.end(), 1)));
  EXPECT_EQ(scan.blocks(), block.size());
  std::vector<std::uint8_t> covered(std::size_t(w) * h, 0);
  for (const rviz_projector::TexelRect& r : rects)
  {
    ASSERT_LT(r.x0, r.x1);
    ASSERT_LT(r.y0, r.y1);
    ASSERT_LE(r.x1, w);
    ASSERT_LE(r.y1, h);
    for (std::uint32_t y = r.y0; y < r.y1; ++y)
    {
      for (std::uint32_t x = r.x0; x < r.x1; ++x)
      {
        ASSERT_EQ(covered[std::size_t(y) * w + x], 0) << "rectangles overlap at (" << x << ", " << y << ")";
        covered[std::size_t(y) * w + x] = 1;
        ASSERT_TRUE(block[std::size_t(y / kB) * bw + x / kB])
            << "(" << x << ", " << y << ") painted, but its block holds nothing but background";
      }
    }
  }
  for (std::uint32_t y = 0; y < h; ++y)
  {
    for (std::uint32_t x = 0; x < w; ++x)
    {
      if (block[std::size_t(y / kB) * bw + x / kB])
      {
        ASSERT_TRUE(covered[std::size_t(y) * w + x]) << "(" << x << ", " << y << ") of a lit block not painted";
      }
    }
  }
  // The bar (blocks 100-101 across, rows 5-29) is one rectangle: runs merge downwards.
  EXPECT_EQ(std::count_if(rects.begin(), rects.end(),
                          [](const rviz_projector::TexelRect& r) {
                            return r.x0 == 800 && r.x1 == 816 && r.y0 == 40 && r.y1 == 240;
                          }),
            1);
  // Nothing lit: nothing to paint. A picture not read back whole: all of it.
  std::fill(picture.begin(), picture.end(), 0xFF000000u);
  scan.scan(picture.data(), w, h, w, 0xFF000000u, 0x00FFFFFFu, occupied);
  scan.litRects(rects);
  EXPECT_TRUE(rects.empty());
  EXPECT_EQ(scan.litBlocks(), 0u);
  scan.begin(0xFF000000u, 0x00FFFFFFu);
  scan.addRows(picture.data(), 0, h - 1, w);
  scan.finish(occupied);
  EXPECT_FALSE(scan.complete());
  scan.litRects(rects);
  ASSERT_EQ(rects.size(), 1u);
  EXPECT_EQ(rects[0].x1 - rects[0].x0, w);
  EXPECT_EQ(rects[0].y1 - rects[0].y0, h);
  EXPECT_EQ(scan.litBlocks(), scan.blocks());
}

// The byte OpenGL stores for a colour component (the warp's background reference and its eraser's
// colour): round(255 c) of c clamped to 0..1; by hand.
TEST(Unorm8, IsOpenGLsRoundingOfTheClampedComponent)
{
  EXPECT_EQ(rviz_projector::unorm8(0.0f), 0);
  EXPECT_EQ(rviz_projector::unorm8(1.0f), 255);
  EXPECT_EQ(rviz_projector::unorm8(20.0f / 255.0f), 20);
  EXPECT_EQ(rviz_projector::unorm8(0.5f), 128);    // 127.5 rounds up (OGRE's packColour gave 128 too)
  EXPECT_EQ(rviz_projector::unorm8(0.299f), 76);   // 76.245 (OGRE's truncation of 256 c: 76)
  EXPECT_EQ(rviz_projector::unorm8(0.302f), 77);   // 77.01 (OGRE's truncation of 256 c: 77)
  EXPECT_EQ(rviz_projector::unorm8(0.6f), 153);    // 153.0 (OGRE's truncation of 256 c: 153)
  EXPECT_EQ(rviz_projector::unorm8(0.75f), 191);   // 191.25 (OGRE's truncation of 256 c: 192)
  EXPECT_EQ(rviz_projector::unorm8(-0.2f), 0);
  EXPECT_EQ(rviz_projector::unorm8(7.0f), 255);
  EXPECT_EQ(rviz_projector::unorm8(std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(rviz_projector::unorm8(std::numeric_limits<float>::infinity()), 255);
}
