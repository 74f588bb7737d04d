#include "rviz_projector/core/warp_cells.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "rviz_projector/core/ascii_lower.h"

namespace rviz_projector
{
namespace
{
std::uint32_t clampIndex(double v, std::uint32_t size)
{
  if (!(v > 0.0))  // NaN too: the whole range stays reachable through the other end
  {
    return 0;
  }
  return v >= double(size) ? size : static_cast<std::uint32_t>(v);
}
}  // namespace

std::vector<CellFootprint> cellFootprints(const WarpGrid& grid)
{
  std::vector<CellFootprint> cells;
  const std::uint32_t w = grid.ideal_lens.width();
  const std::uint32_t h = grid.ideal_lens.height();
  cells.reserve(std::size_t(grid.columns) * grid.rows);
  for (std::uint32_t j = 0; j < grid.rows; ++j)
  {
    for (std::uint32_t i = 0; i < grid.columns; ++i)
    {
      double min_x = std::numeric_limits<double>::infinity(), min_y = min_x;
      double max_x = -min_x, max_y = -min_x;
      for (const std::size_t v : {grid.vertexIndex(i, j), grid.vertexIndex(i + 1, j), grid.vertexIndex(i, j + 1),
                                  grid.vertexIndex(i + 1, j + 1)})
      {
        min_x = std::min(min_x, grid.ideal[v].x);
        max_x = std::max(max_x, grid.ideal[v].x);
        min_y = std::min(min_y, grid.ideal[v].y);
        max_y = std::max(max_y, grid.ideal[v].y);
      }
      // Texel centres at integers: a sample at p reads floor(p) and floor(p) + 1; one more each side.
      CellFootprint f;
      f.x0 = clampIndex(std::floor(min_x) - 1.0, w);
      f.y0 = clampIndex(std::floor(min_y) - 1.0, h);
      f.x1 = clampIndex(std::floor(max_x) + 3.0, w);
      f.y1 = clampIndex(std::floor(max_y) + 3.0, h);
      // Clamp-to-edge addressing: a cell beyond the image reads its edge texels.
      if (w > 0 && h > 0)
      {
        f.x0 = std::min(f.x0, w - 1);
        f.y0 = std::min(f.y0, h - 1);
        f.x1 = std::max(f.x1, f.x0 + 1);
        f.y1 = std::max(f.y1, f.y0 + 1);
      }
      cells.push_back(f);
    }
  }
  return cells;
}

WarpCellScan::WarpCellScan(const WarpGrid& grid)
  : footprints_(cellFootprints(grid))
  , width_(grid.ideal_lens.width())
  , height_(grid.ideal_lens.height())
  , blocks_x_((width_ + kBlock - 1) / kBlock)
  , blocks_y_((height_ + kBlock - 1) / kBlock)
  , blocks_(std::size_t(blocks_x_) * blocks_y_, 0)
{
}

std::size_t WarpCellScan::scan(const std::uint32_t* pixels, std::uint32_t width, std::uint32_t height,
                               std::size_t stride, std::uint32_t background, std::uint32_t mask,
                               std::vector<std::uint8_t>& occupied)
{
  begin(background, mask);
  if (pixels == nullptr || width != width_ || height != height_ || stride < width)
  {
    broken_ = true;
  }
  else
  {
    addRows(pixels, 0, height, stride);
  }
  return finish(occupied);
}

void WarpCellScan::begin(std::uint32_t background, std::uint32_t mask)
{
  reference_ = background & mask;
  mask_ = mask;
  next_row_ = 0;
  broken_ = false;
  std::fill(blocks_.begin(), blocks_.end(), 0);
}

void WarpCellScan::addRows(const std::uint32_t* rows, std::uint32_t y0, std::uint32_t count, std::size_t stride)
{
  if (broken_ || rows == nullptr || y0 != next_row_ || count > height_ - y0 || stride < width_)
  {
    broken_ = true;
    return;
  }
  const std::uint32_t full_blocks = width_ / kBlock;
  const std::uint64_t mask2 = (std::uint64_t(mask_) << 32) | mask_;
  const std::uint64_t reference2 = (std::uint64_t(reference_) << 32) | reference_;
  for (std::uint32_t r = 0; r < count; ++r)
  {
    const std::uint32_t* row = rows + std::size_t(r) * stride;
    std::uint8_t* block_row = blocks_.data() + std::size_t((y0 + r) / kBlock) * blocks_x_;
    for (std::uint32_t bx = 0; bx < full_blocks; ++bx)
    {
      if (block_row[bx])
      {
        continue;  // already drawn: nothing in it can change that
      }
      // Two pixels per 64-bit word, a fixed count of words: vector code without intrinsics.
      const std::uint32_t* p = row + std::size_t(bx) * kBlock;
      std::uint64_t differs = 0;
      for (std::uint32_t x = 0; x < kBlock; x += 2)
      {
        std::uint64_t two;
        std::memcpy(&two, p + x, sizeof(two));
        differs |= (two ^ reference2) & mask2;
      }
      block_row[bx] = differs != 0 ? 1 : 0;
    }
    if (full_blocks < blocks_x_ && !block_row[full_blocks])  // the narrower last block
    {
      std::uint32_t differs = 0;
      for (std::uint32_t x = full_blocks * kBlock; x < width_; ++x)
      {
        differs |= (row[x] & mask_) ^ reference_;
      }
      block_row[full_blocks] = differs != 0 ? 1 : 0;
    }
  }
  next_row_ = y0 + count;
}

std::size_t WarpCellScan::finish(std::vector<std::uint8_t>& occupied)
{
  if (!complete())
  {
    lit_blocks_ = blocks_.size();
    occupied.assign(footprints_.size(), 1);
    return footprints_.size();
  }
  lit_blocks_ = static_cast<std::size_t>(std::count(blocks_.begin(), blocks_.end(), std::uint8_t(1)));
  occupied.assign(footprints_.size(), 0);
  std::size_t count = 0;
  for (std::size_t c = 0; c < footprints_.size(); ++c)
  {
    const CellFootprint& f = footprints_[c];
    bool any = false;
    for (std::uint32_t by = f.y0 / kBlock; by <= (f.y1 - 1) / kBlock && !any; ++by)
    {
      for (std::uint32_t bx = f.x0 / kBlock; bx <= (f.x1 - 1) / kBlock; ++bx)
      {
        if (blocks_[std::size_t(by) * blocks_x_ + bx])
        {
          any = true;
          break;
        }
      }
    }
    occupied[c] = any ? 1 : 0;
    count += any ? 1 : 0;
  }
  return count;
}

void WarpCellScan::litRects(std::vector<TexelRect>& rects) const
{
  rects.clear();
  if (!complete())
  {
    rects.push_back({0, 0, width_, height_});
    return;
  }
  // Runs of lit blocks along each block row; a run open since earlier rows grows down while the
  // same run follows (a vertical bar or a disc's middle rows: one rectangle instead of many).
  std::vector<TexelRect> open;  // runs of the previous block row, in block units
  std::vector<TexelRect> next;
  auto close = [&](const TexelRect& run) {
    rects.push_back({run.x0 * kBlock, run.y0 * kBlock, std::min(run.x1 * kBlock, width_),
                     std::min(run.y1 * kBlock, height_)});
  };
  for (std::uint32_t by = 0; by <= blocks_y_; ++by)
  {
    next.clear();
    std::size_t o = 0;  // open runs are sorted by x0: walk them along the row
    for (std::uint32_t bx = 0; by < blocks_y_ && bx < blocks_x_;)
    {
      if (!blocks_[std::size_t(by) * blocks_x_ + bx])
      {
        ++bx;
        continue;
      }
      const std::uint32_t x0 = bx;
      while (bx < blocks_x_ && blocks_[std::size_t(by) * blocks_x_ + bx])
      {
        ++bx;
      }
      while (o < open.size() && open[o].x0 < x0)
      {
        close(open[o++]);
      }
      if (o < open.size() && open[o].x0 == x0 && open[o].x1 == bx)
      {
        next.push_back({x0, open[o].y0, bx, by + 1});  // the same run: one rectangle grows
        ++o;
      }
      else
      {
        next.push_back({x0, by, bx, by + 1});
      }
    }
    for (; o < open.size(); ++o)
    {
      close(open[o]);
    }
    open.swap(next);
  }
}

WarpCells chooseWarpCells(const std::string& setting, const std::string& renderer, std::string* error)
{
  const std::string s = asciiLower(setting);
  if (s == "all")
  {
    return WarpCells::All;
  }
  if (s == "occupied")
  {
    return WarpCells::Occupied;
  }
  if (!s.empty() && s != "auto" && error)
  {
    *error = "RVIZ_PROJECTOR_WARP_CELLS='" + setting + "' is not one of all, occupied, auto: auto is used";
  }
  const std::string r = asciiLower(renderer);
  const bool software = r.find("llvmpipe") != std::string::npos || r.find("softpipe") != std::string::npos ||
                        r.find("swrast") != std::string::npos || r.find("software rasterizer") != std::string::npos;
  return software ? WarpCells::Occupied : WarpCells::All;
}
}  // namespace rviz_projector
