#include "rviz_projector/core/warp_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rviz_projector
{
Vec2 WarpGrid::textureCoordinate(std::size_t vertex) const
{
  const Vec2& p = ideal[vertex];
  return {(p.x + 0.5) / double(ideal_lens.width()), (p.y + 0.5) / double(ideal_lens.height())};
}

WarpGrid makeWarpGrid(const PinholeModel& raw_lens, const LensDistortion& distortion, std::uint32_t columns,
                      std::uint32_t rows)
{
  WarpGrid grid;
  grid.columns = std::max<std::uint32_t>(columns, 1);
  grid.rows = std::max<std::uint32_t>(rows, 1);
  const double w = raw_lens.width();
  const double h = raw_lens.height();
  std::vector<Vec2> normalised;
  normalised.reserve((grid.columns + 1) * (grid.rows + 1));
  for (std::uint32_t j = 0; j <= grid.rows; ++j)
  {
    for (std::uint32_t i = 0; i <= grid.columns; ++i)
    {
      const Vec2 pixel{-0.5 + w * i / grid.columns, -0.5 + h * j / grid.rows};
      grid.raw.push_back(pixel);
      const Vec3 ray = raw_lens.ray(pixel);
      normalised.push_back({ray.x, ray.y});
    }
  }
  const std::vector<Vec2> rays = distortion.undistort(normalised);

  // The ideal pinhole: the lens's focal lengths (scaled up where the lens spreads the picture,
  // down if the reach is very wide), its image the bounding box of every vertex's ray plus a pixel,
  // its principal point moved with it.
  double min_x = std::numeric_limits<double>::infinity(), min_y = min_x;
  double max_x = -min_x, max_y = -min_x;
  for (const Vec2& r : rays)
  {
    min_x = std::min(min_x, r.x);
    max_x = std::max(max_x, r.x);
    min_y = std::min(min_y, r.y);
    max_y = std::max(max_y, r.y);
  }
  // Nowhere fewer ideal pixels than raw ones: where the lens spreads the picture (a pincushion's
  // corners) the ideal render is drawn at a higher resolution, so the warp never magnifies it
  // (a magnified texture blurs: a target's centroid moved 0.26 px at k1 = +0.10 without this).
  double least = 1.0;  // fewest ideal pixels per raw pixel along a cell's edge, at scale 1
  for (std::uint32_t j = 0; j <= grid.rows; ++j)
  {
    for (std::uint32_t i = 0; i <= grid.columns; ++i)
    {
      const Vec2& r = rays[grid.vertexIndex(i, j)];
      if (i < grid.columns)
      {
        least = std::min(least, raw_lens.fx() * std::abs(rays[grid.vertexIndex(i + 1, j)].x - r.x) / (w / grid.columns));
      }
      if (j < grid.rows)
      {
        least = std::min(least, raw_lens.fy() * std::abs(rays[grid.vertexIndex(i, j + 1)].y - r.y) / (h / grid.rows));
      }
    }
  }
  const double sharp = least > 0.0 ? 1.0 / least : 1.0;
  const double span_x = (max_x - min_x) * raw_lens.fx();
  const double span_y = (max_y - min_y) * raw_lens.fy();
  const double scale = std::min({sharp, WarpGrid::kMaxOversize * w / std::max(span_x, 1.0),
                                 WarpGrid::kMaxOversize * h / std::max(span_y, 1.0)});
  const double fx = raw_lens.fx() * scale;
  const double fy = raw_lens.fy() * scale;
  // Ideal pixel of a ray with the raw principal point: c + f r; its image starts a pixel before
  // the smallest one (an edge at an integer - 0.5).
  const double left = std::floor(raw_lens.cx() * scale + fx * min_x) - 1.0;
  const double top = std::floor(raw_lens.cy() * scale + fy * min_y) - 1.0;
  const double right = std::ceil(raw_lens.cx() * scale + fx * max_x) + 1.0;
  const double bottom = std::ceil(raw_lens.cy() * scale + fy * max_y) + 1.0;
  const double cx = raw_lens.cx() * scale - left;
  const double cy = raw_lens.cy() * scale - top;
  grid.ideal_lens = PinholeModel(static_cast<std::uint32_t>(right - left + 1.0),
                                 static_cast<std::uint32_t>(bottom - top + 1.0), fx, fy, cx, cy);
  grid.ideal.reserve(rays.size());
  for (const Vec2& r : rays)
  {
    grid.ideal.push_back({cx + fx * r.x, cy + fy * r.y});
  }
  return grid;
}

double warpGridError(const WarpGrid& grid, const PinholeModel& raw_lens, const LensDistortion& distortion,
                     int samples)
{
  samples = std::max(samples, 1);
  std::vector<Vec2> wanted;    // raw pixel of each sample (where it must land)
  std::vector<Vec2> drawn;     // the normalised ideal ray the grid gives it
  const PinholeModel& ideal = grid.ideal_lens;
  for (std::uint32_t j = 0; j < grid.rows; ++j)
  {
    for (std::uint32_t i = 0; i < grid.columns; ++i)
    {
      const Vec2& r00 = grid.raw[grid.vertexIndex(i, j)];
      const Vec2& r11 = grid.raw[grid.vertexIndex(i + 1, j + 1)];
      const Vec2& a = grid.ideal[grid.vertexIndex(i, j)];
      const Vec2& b = grid.ideal[grid.vertexIndex(i + 1, j)];
      const Vec2& c = grid.ideal[grid.vertexIndex(i, j + 1)];
      const Vec2& d = grid.ideal[grid.vertexIndex(i + 1, j + 1)];
      for (int sy = 0; sy < samples; ++sy)
      {
        for (int sx = 0; sx < samples; ++sx)
        {
          const double s = (sx + 0.5) / samples;
          const double t = (sy + 0.5) / samples;
          wanted.push_back({r00.x + s * (r11.x - r00.x), r00.y + t * (r11.y - r00.y)});
          // Two triangles per cell, split along b-c (as the mesh is drawn): affine in each.
          const Vec2 p = s + t <= 1.0 ? Vec2{a.x + s * (b.x - a.x) + t * (c.x - a.x), a.y + s * (b.y - a.y) + t * (c.y - a.y)}
                                      : Vec2{d.x + (1 - s) * (c.x - d.x) + (1 - t) * (b.x - d.x),
                                             d.y + (1 - s) * (c.y - d.y) + (1 - t) * (b.y - d.y)};
          const Vec3 ray = ideal.ray(p);
          drawn.push_back({ray.x, ray.y});
        }
      }
    }
  }
  const std::vector<Vec2> lit = distortion.distort(drawn);
  double worst = 0.0;
  for (std::size_t k = 0; k < lit.size(); ++k)
  {
    const Vec2 pixel{raw_lens.cx() + raw_lens.fx() * lit[k].x, raw_lens.cy() + raw_lens.fy() * lit[k].y};
    worst = std::max(worst, std::hypot(pixel.x - wanted[k].x, pixel.y - wanted[k].y));
  }
  return worst;
}
}  // namespace rviz_projector
