// WarpCellScan and chooseWarpCells (issue 24: the warp on a software renderer draws only the cells
// with something on them). The oracle: each cell's two triangles sampled densely here, each sample
// interpolated as the GPU does (affine in the triangle) and read bilinearly (the texel at or before
// it and the next, clamped to the image), written independently of warp_cells.cpp. A cell that reads
// a lit texel must be drawn; a picture with nothing on it draws no cell.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "rviz_projector/core/lens_distortion.h"
#include "rviz_projector/core/pinhole_model.h"
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

/// Texels (x + y * width) each cell reads, from 25 x 25 samples of each of its triangles.
std::vector<std::set<std::uint32_t>> texelsRead(const WarpGrid& g)
{
  const int w = int(g.ideal_lens.width());
  const int h = int(g.ideal_lens.height());
  std::vector<std::set<std::uint32_t>> cells;
  for (std::uint32_t j = 0; j < g.rows; ++j)
  {
    for (std::uint32_t i = 0; i < g.columns; ++i)
    {
      const Vec2 a = g.ideal[j * (g.columns + 1) + i];
      const Vec2 b = g.ideal[j * (g.columns + 1) + i + 1];
      const Vec2 c = g.ideal[(j + 1) * (g.columns + 1) + i];
      const Vec2 d = g.ideal[(j + 1) * (g.columns + 1) + i + 1];
      std::set<std::uint32_t> read;
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
                read.insert(std::uint32_t(x + y * w));
              }
            }
          }
        }
      }
      cells.push_back(read);
    }
  }
  return cells;
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
  const WarpGrid g = wideGrid();
  const std::vector<std::set<std::uint32_t>> oracle = texelsRead(g);
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
    std::size_t readers = 0;
    for (std::size_t c = 0; c < oracle.size(); ++c)
    {
      if (oracle[c].count(index))
      {
        ++readers;
        EXPECT_TRUE(occupied[c]) << "cell " << c << " reads texel (" << t.first << ", " << t.second
                                 << ") but is not drawn";
      }
    }
    EXPECT_GE(count, readers);
    most = std::max(most, count);
    ++checked;
  }
  EXPECT_GT(checked, 1500);
  // A 16 x 16 block and a texel of margin: a lit texel draws at most the 3 x 3 cells around it.
  EXPECT_LE(most, 9u) << "a single lit texel drew " << most << " cells";
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
// size finds the cells that read a lit texel (the texelsRead oracle) and the same cells as the
// whole picture at once.
TEST(WarpCellScan, StripsOfAnySizeFindTheCellsOfTheWholePicture)
{
  const WarpGrid g = wideGrid();
  const std::vector<std::set<std::uint32_t>> oracle = texelsRead(g);
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
  for (std::size_t c = 0; c < oracle.size(); ++c)
  {
    for (const std::uint32_t t : lit)
    {
      if (oracle[c].count(t))
      {
        EXPECT_TRUE(whole[c]) << "cell " << c << " reads lit texel " << t;
      }
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
