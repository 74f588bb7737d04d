#include "rviz_projector/core/floor_grid.h"

#include <algorithm>
#include <cmath>

namespace rviz_projector
{
namespace
{
void appendRectangle(const Vec2& a, const Vec2& b, std::vector<Vec2>& out)
{
  const Vec2 c{b.x, a.y}, d{a.x, b.y};
  out.insert(out.end(), {a, c, b, a, b, d});
}

/// Index range of grid lines k * cell within [lo, hi], bounded to kMaxLines lines.
void lineRange(double lo, double hi, double cell, long& first, long& last)
{
  // Line indices must fit a long; a grid that far from the origin (1e15 cells) draws no lines.
  constexpr double kMaxIndex = 1e15;
  if (!(std::abs(lo / cell) <= kMaxIndex) || !(std::abs(hi / cell) <= kMaxIndex))
  {
    first = 1;
    last = 0;
    return;
  }
  first = static_cast<long>(std::ceil(lo / cell));
  last = static_cast<long>(std::floor(hi / cell));
  last = std::min(last, first + FloorGrid::kMaxLines - 1);
}
}  // namespace

FloorGrid::FloorGrid(const Vec2& min, const Vec2& max, double cell)
  : min_(min), max_(max), cell_(std::isfinite(cell) && cell > 1e-3 ? cell : 0.1)
{
  if (!isFinite(min_) || !isFinite(max_) || min_.x > max_.x || min_.y > max_.y)
  {
    min_ = max_ = Vec2{};
  }
}

int FloorGrid::verticalLineCount() const
{
  long first, last;
  lineRange(min_.x, max_.x, cell_, first, last);
  return static_cast<int>(std::max(0L, last - first + 1));
}

void FloorGrid::appendTriangles(std::vector<Vec2>& out) const
{
  if (min_.x == max_.x || min_.y == max_.y)
  {
    return;
  }
  const long per_metre = std::max(1L, std::lround(1.0 / cell_));
  long first, last;
  lineRange(min_.x, max_.x, cell_, first, last);
  for (long k = first; k <= last; ++k)
  {
    const double half = 0.5 * (k % per_metre == 0 ? kMetreLineWidth : kCellLineWidth);
    const double x = k * cell_;
    appendRectangle({x - half, min_.y}, {x + half, max_.y}, out);
  }
  lineRange(min_.y, max_.y, cell_, first, last);
  for (long k = first; k <= last; ++k)
  {
    const double half = 0.5 * (k % per_metre == 0 ? kMetreLineWidth : kCellLineWidth);
    const double y = k * cell_;
    appendRectangle({min_.x, y - half}, {max_.x, y + half}, out);
  }
  // Origin: a bold cross, three metre-lines wide.
  const double w = 1.5 * kMetreLineWidth;
  appendRectangle({-kOriginMark, -w}, {kOriginMark, w}, out);
  appendRectangle({-w, -kOriginMark}, {w, kOriginMark}, out);
}
}  // namespace rviz_projector
