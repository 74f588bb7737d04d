// The warp that draws through a distorting lens (issue 24): the scene is rendered as an ideal
// pinhole to a texture (larger than the lens's image where a barrel lens reaches further), and a
// grid of cells over the lens's raw image samples that texture where each raw pixel's ray lands.
// Inside a cell the GPU interpolates linearly; warpGridError() measures what that costs.
#pragma once

#include <cstdint>
#include <vector>

#include "rviz_projector/core/lens_distortion.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
struct WarpGrid
{
  static constexpr std::uint32_t kDefaultColumns = 32;
  static constexpr std::uint32_t kDefaultRows = 20;
  /// The ideal render has at least one pixel per raw pixel everywhere (its focal lengths scaled
  /// up where the lens spreads the picture), and is at most this many times the raw image per axis
  /// (a wider reach is drawn at a lower resolution: the focal lengths are scaled down).
  static constexpr double kMaxOversize = 2.0;

  std::uint32_t columns = 0;  ///< cells across
  std::uint32_t rows = 0;     ///< cells down
  /// (columns + 1) x (rows + 1) vertices, row by row: raw (distorted) pixel coordinates (OpenCV's
  /// convention, centres at integers) spread evenly over the raw image's outer edges, -0.5 ..
  /// width - 0.5 and -0.5 .. height - 0.5.
  std::vector<Vec2> raw;
  /// The same rays in pixels of `ideal_lens` (pixel centres at integers).
  std::vector<Vec2> ideal;
  /// The pinhole to render the scene with: every vertex's ray inside its image.
  PinholeModel ideal_lens;

  std::size_t vertexIndex(std::uint32_t column, std::uint32_t row) const { return row * (columns + 1) + column; }
  /// Texture coordinates (0..1 across ideal_lens's image, u right, v down) of a vertex.
  Vec2 textureCoordinate(std::size_t vertex) const;
};

/**
 * The grid for a lens: `raw_lens` is K's pinhole over the raw image (the pixels the projector
 * lights), `distortion` its D. The distortion must not fold inside the image
 * (LensDistortion::foldCheck; PinholeModel::fromCalibration refuses such a lens).
 */
WarpGrid makeWarpGrid(const PinholeModel& raw_lens, const LensDistortion& distortion,
                      std::uint32_t columns = WarpGrid::kDefaultColumns, std::uint32_t rows = WarpGrid::kDefaultRows);

/**
 * Largest distance, raw pixels, between where the grid draws a ray and where the lens does:
 * `samples` x `samples` points per cell, each interpolated as the GPU does it (a cell is two
 * triangles, (i, j) (i+1, j) (i, j+1) and (i+1, j) (i+1, j+1) (i, j+1), affine inside each) and
 * sent back through the lens.
 */
double warpGridError(const WarpGrid& grid, const PinholeModel& raw_lens, const LensDistortion& distortion,
                     int samples = 4);
}  // namespace rviz_projector
