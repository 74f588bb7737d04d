// Which cells of a warp grid (warp_grid.h) have anything to draw. A projector's picture is mostly
// background (black: no light); on a software renderer (llvmpipe) drawing the warp's mesh costs
// ~12 ns per window pixel whatever the pixel shows, while a cleared window costs almost nothing.
// So the warp can draw only the cells whose texels are not all background: the others would show
// exactly the background colour (a bilinear sample of equal texels is that texel), which the
// window's clear already shows. Never drops a cell that could show anything else.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "rviz_projector/core/warp_grid.h"

namespace rviz_projector
{
/// Texels [x0, x1) x [y0, y1) of a picture (the ideal render).
struct TexelRect
{
  std::uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

inline bool operator==(const TexelRect& a, const TexelRect& b)
{
  return a.x0 == b.x0 && a.y0 == b.y0 && a.x1 == b.x1 && a.y1 == b.y1;
}

/// The texels a cell of the grid can read, in ideal pixels, clamped to the ideal image. Inside a
/// cell the GPU interpolates the texture coordinates of its two triangles, so every sample lies in
/// the bounding box of the cell's four vertices; a bilinear sample reads the texel at or before it
/// and the next one; one texel more on each side absorbs the GPU's limited sub-texel precision.
using CellFootprint = TexelRect;

/// One footprint per cell, row by row (cell (i, j) at j * columns + i).
std::vector<CellFootprint> cellFootprints(const WarpGrid& grid);

/// Finds the cells with anything but background. The picture is 32-bit pixels, `stride` pixels
/// per row, `width` x `height` (the grid's ideal image). Pixels are compared with `background` on
/// the bits of `mask` (e.g. the colour channels without alpha).
/// The picture can come whole (scan()) or in strips of rows, top to bottom (begin(), addRows(),
/// finish()): a strip read back from the renderer and scanned at once stays in the CPU's cache.
class WarpCellScan
{
public:
  /// Edge of the square blocks the picture is summarised in (one pass over the picture; then each
  /// cell looks only at its blocks). A block counts as drawn if any pixel of it is. The lit blocks
  /// are also what the warp's eraser paints back to the background (litRects()): small blocks paint
  /// little more than what is lit.
  static constexpr std::uint32_t kBlock = 8;

  explicit WarpCellScan(const WarpGrid& grid);

  /// `occupied` gets one entry per cell (non-zero: draw it). Returns how many cells are occupied.
  /// A picture of another size than the grid's ideal image: every cell occupied (never drops).
  std::size_t scan(const std::uint32_t* pixels, std::uint32_t width, std::uint32_t height, std::size_t stride,
                   std::uint32_t background, std::uint32_t mask, std::vector<std::uint8_t>& occupied);

  /// Starts a picture given in strips.
  void begin(std::uint32_t background, std::uint32_t mask);
  /// Rows [y0, y0 + count) of the picture, `stride` pixels apart, each `width` pixels (the grid's
  /// ideal width). Strips must follow each other from row 0 down; one out of order, or of another
  /// width, makes finish() draw every cell.
  void addRows(const std::uint32_t* rows, std::uint32_t y0, std::uint32_t count, std::size_t stride);
  /// The cells, as scan(). Unless every row of the picture came, in order: every cell (never drops).
  std::size_t finish(std::vector<std::uint8_t>& occupied);

  /// After finish() or scan(): every row of the picture came, in order (only then is litRects()
  /// the picture's).
  bool complete() const { return !broken_ && next_row_ == height_ && height_ > 0; }
  /// After a complete picture: the pixels of the blocks with anything but background on the mask's
  /// bits, as rectangles [x0, x1) x [y0, y1) clamped to the picture (each block row's runs of such
  /// blocks, a run merged with the same run in the rows below). Every pixel outside them is
  /// background. An incomplete picture: one rectangle, the whole picture.
  void litRects(std::vector<TexelRect>& rects) const;
  /// Of the last picture: blocks with anything but background, and all its blocks.
  std::size_t litBlocks() const { return lit_blocks_; }
  std::size_t blocks() const { return blocks_.size(); }

private:
  std::vector<CellFootprint> footprints_;
  std::uint32_t width_ = 0, height_ = 0;
  std::uint32_t blocks_x_ = 0, blocks_y_ = 0;
  std::vector<std::uint8_t> blocks_;  // per block: any pixel not background
  std::uint32_t reference_ = 0, mask_ = 0;  // background & mask, mask
  std::uint32_t next_row_ = 0;  // rows [0, next_row_) summarised
  bool broken_ = false;  // a strip out of order: every cell
  std::size_t lit_blocks_ = 0;  // counted by finish()
};

/// Which cells the warp draws. All: every cell, always (one pass over every window pixel). Occupied:
/// read the ideal render back and draw only the cells with something on them (the window cleared
/// first): cheaper on a software renderer, where every drawn pixel costs CPU time, dearer on a GPU,
/// where the read-back stalls it.
enum class WarpCells
{
  All,
  Occupied
};

/// The choice: `setting` is RVIZ_PROJECTOR_WARP_CELLS ("all", "occupied", or empty/"auto");
/// `renderer` the GL renderer's name (GL_RENDERER). Auto: Occupied on Mesa's software renderers
/// (llvmpipe, softpipe, swrast), All on anything else. `error` gets a message for a setting that
/// is none of these (the choice is then auto).
WarpCells chooseWarpCells(const std::string& setting, const std::string& renderer, std::string* error = nullptr);
}  // namespace rviz_projector
