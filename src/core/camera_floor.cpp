// Camera pixels -> floor, decoded structured light -> correspondences; see camera_floor.h.
#include "rviz_projector/core/camera_floor.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rviz_projector/core/lens_distortion.h"

namespace rviz_projector
{
namespace
{
const double kNaN = std::numeric_limits<double>::quiet_NaN();

bool finiteTransform(const RigidTransform& t)
{
  for (double r : t.rotation())
  {
    if (!std::isfinite(r))
    {
      return false;
    }
  }
  return isFinite(t.translation());
}

/// Sufficient statistics of an affine least-squares fit (x, y) -> t, x and y relative to the image
/// centre (for accuracy).
struct Sums
{
  double n = 0, x = 0, y = 0, xx = 0, xy = 0, yy = 0, t = 0, xt = 0, yt = 0;
  void add(double sx, double sy, double st)
  {
    n += 1;
    x += sx;
    y += sy;
    xx += sx * sx;
    xy += sx * sy;
    yy += sy * sy;
    t += st;
    xt += sx * st;
    yt += sy * st;
  }
  void add(const Sums& o)
  {
    n += o.n;
    x += o.x;
    y += o.y;
    xx += o.xx;
    xy += o.xy;
    yy += o.yy;
    t += o.t;
    xt += o.xt;
    yt += o.yt;
  }
};

/// t = mean + a (x - mx) + b (y - my).
struct Affine
{
  double mean = 0, mx = 0, my = 0, a = 0, b = 0;
  double at(double x, double y) const { return mean + a * (x - mx) + b * (y - my); }
};

/// The fit of the sums; false when ill-conditioned (fewer than 6 samples, or camera positions
/// (nearly) on a line).
bool fitAffine(const Sums& s, Affine& out)
{
  if (s.n < 6)
  {
    return false;
  }
  const double mx = s.x / s.n, my = s.y / s.n, mt = s.t / s.n;
  const double cxx = s.xx / s.n - mx * mx, cxy = s.xy / s.n - mx * my, cyy = s.yy / s.n - my * my;
  const double det = cxx * cyy - cxy * cxy;
  const double trace = cxx + cyy;
  if (!(trace > 0.0) || det <= 1e-3 * trace * trace)
  {
    return false;
  }
  const double cxt = s.xt / s.n - mx * mt, cyt = s.yt / s.n - my * mt;
  out.mean = mt;
  out.mx = mx;
  out.my = my;
  out.a = (cyy * cxt - cxy * cyt) / det;
  out.b = (cxx * cyt - cxy * cxt) / det;
  return true;
}

/// Cell grid of the projector image.
struct Grid
{
  int cell = 8, cells_x = 0, cells_y = 0;
  int clampX(int c) const { return std::min(std::max(c, 0), cells_x - 1); }
  int clampY(int c) const { return std::min(std::max(c, 0), cells_y - 1); }
  std::size_t index(int cx, int cy) const { return std::size_t(cy) * std::size_t(cells_x) + std::size_t(cx); }
  std::size_t of(double u, double v) const
  {
    return index(clampX(int(std::floor(u / cell))), clampY(int(std::floor(v / cell))));
  }
};

/// Sum of the per-cell sums over the (2r + 1)^2 window around a cell.
Sums windowSums(const std::vector<Sums>& sums, const Grid& grid, std::size_t c, int r)
{
  const int cx = int(c % std::size_t(grid.cells_x)), cy = int(c / std::size_t(grid.cells_x));
  Sums out;
  for (int wy = std::max(0, cy - r); wy <= std::min(grid.cells_y - 1, cy + r); ++wy)
  {
    for (int wx = std::max(0, cx - r); wx <= std::min(grid.cells_x - 1, cx + r); ++wx)
    {
      out.add(sums[grid.index(wx, wy)]);
    }
  }
  return out;
}
}  // namespace

std::string cameraLensProblem(const LensCalibration& camera)
{
  const std::array<double, 9>& K = camera.K;
  for (double k : K)
  {
    if (!std::isfinite(k))
    {
      return "camera K is not finite";
    }
  }
  if (!(K[0] > 0.0) || !(K[4] > 0.0))
  {
    return "camera focal lengths (K) are not positive";
  }
  if (K[1] != 0.0 || K[3] != 0.0 || K[6] != 0.0 || K[7] != 0.0 || K[8] != 1.0)
  {
    return "camera K is not [fx 0 cx; 0 fy cy; 0 0 1] (skew or a scaled matrix are not supported)";
  }
  if (camera.binning_x > 1 || camera.binning_y > 1)
  {
    return "camera binning " + std::to_string(camera.binning_x) + "x" + std::to_string(camera.binning_y) +
           " is not supported (full-resolution captures only)";
  }
  const bool no_roi = camera.roi_x_offset == 0 && camera.roi_y_offset == 0 && camera.roi_width == 0 &&
                      camera.roi_height == 0;
  const bool whole_roi = camera.roi_x_offset == 0 && camera.roi_y_offset == 0 && camera.roi_width == camera.width &&
                         camera.roi_height == camera.height;
  if (!no_roi && !whole_roi)
  {
    return "camera region of interest is not the whole image (full-frame captures only)";
  }
  LensDistortion distortion;
  const LensCheck check = LensDistortion::fromCalibration(camera, distortion);
  if (!check.ok())
  {
    return "camera distortion: " + check.error;
  }
  if (camera.width > 0 && camera.height > 0 && !distortion.none())
  {
    double corner = 0.0;
    for (double px : {-0.5, double(camera.width) - 0.5})
    {
      for (double py : {-0.5, double(camera.height) - 0.5})
      {
        corner = std::max(corner, std::hypot((px - K[2]) / K[0], (py - K[5]) / K[4]));
      }
    }
    const std::string fold = LensDistortion::foldError(distortion.foldCheck(corner), corner);
    if (!fold.empty())
    {
      return "camera distortion: " + fold;
    }
  }
  return "";
}

std::vector<Vec3> cameraPixelsOnPlane(const LensCalibration& camera, const RigidTransform& base_T_camera_optical,
                                      const std::vector<Vec2>& pixels, double plane_z, std::string& error)
{
  if (!std::isfinite(plane_z))
  {
    error = cameraLensProblem(camera);
    if (error.empty())
    {
      error = "floor plane height is not finite";
    }
    return {};
  }
  return cameraPixelsOnPlane(camera, base_T_camera_optical, pixels, Plane{Vec3{0.0, 0.0, 1.0}, plane_z}, error);
}

std::vector<Vec3> cameraPixelsOnPlane(const LensCalibration& camera, const RigidTransform& base_T_camera_optical,
                                      const std::vector<Vec2>& pixels, const Plane& plane, std::string& error)
{
  error = cameraLensProblem(camera);
  if (error.empty() && !finiteTransform(base_T_camera_optical))
  {
    error = "camera pose (base_T_camera_optical) is not finite";
  }
  if (error.empty() && !(isFinite(plane.normal) && std::isfinite(plane.offset) &&
                         std::abs(norm(plane.normal) - 1.0) <= 1e-6))
  {
    error = "the plane is not finite or its normal is not of unit length";
  }
  if (!error.empty())
  {
    return {};
  }
  LensDistortion distortion;
  LensDistortion::fromCalibration(camera, distortion);  // checked above
  const double fx = camera.K[0], fy = camera.K[4], cx = camera.K[2], cy = camera.K[5];
  std::vector<Vec2> normalised;
  normalised.reserve(pixels.size());
  for (const Vec2& p : pixels)
  {
    // A NaN pixel stays NaN through the undistortion; it is turned into a NaN point below.
    normalised.push_back({(p.x - cx) / fx, (p.y - cy) / fy});
  }
  if (!distortion.none())
  {
    normalised = distortion.undistort(normalised);
  }
  const Vec3 origin = base_T_camera_optical.translation();
  const Vec3& n = plane.normal;
  const double origin_height = n.x * origin.x + n.y * origin.y + n.z * origin.z - plane.offset;
  std::vector<Vec3> out(pixels.size(), Vec3{kNaN, kNaN, kNaN});
  for (std::size_t i = 0; i < pixels.size(); ++i)
  {
    if (!isFinite(pixels[i]) || !isFinite(normalised[i]))
    {
      continue;
    }
    const Vec3 d = base_T_camera_optical.rotate(Vec3{normalised[i].x, normalised[i].y, 1.0});
    const double along = n.x * d.x + n.y * d.y + n.z * d.z;
    if (std::abs(along) < 1e-9 * norm(d))
    {
      continue;  // parallel to the plane
    }
    const double s = -origin_height / along;
    if (!(s > 0.0))
    {
      continue;  // behind the camera (or the camera is on the plane)
    }
    out[i] = Vec3{origin.x + s * d.x, origin.y + s * d.y, origin.z + s * d.z};
    if (n.x == 0.0 && n.y == 0.0)
    {
      out[i].z = plane.offset / n.z;  // exactly on a horizontal plane
    }
  }
  return out;
}

Correspondences floorCorrespondences(const GrayDecodeResult& decoded, const LensCalibration& camera,
                                     const RigidTransform& base_T_camera_optical, int projector_width,
                                     int projector_height, const CorrespondenceOptions& options)
{
  Correspondences result;
  if (!decoded.error.empty())
  {
    result.error = "decoding failed: " + decoded.error;
    return result;
  }
  if (decoded.projector.empty() || decoded.projector.type() != CV_32FC2 || decoded.bits.type() != CV_8UC2 ||
      decoded.bits.size() != decoded.projector.size())
  {
    result.error = "decode result has no CV_32FC2 projector image and CV_8UC2 bits image of one size";
    return result;
  }
  if (projector_width < 2 || projector_height < 2 || projector_width > 16384 || projector_height > 16384)
  {
    result.error = "projector size is not 2..16384 pixels in each direction";
    return result;
  }
  if (options.cell < 1 || options.cell > 1024 || options.min_samples < 1 || options.fit_radius < 0 ||
      options.fit_radius > 64 || !std::isfinite(options.plane_z) || !(options.outlier_tolerance >= 0.0) ||
      !std::isfinite(options.outlier_tolerance))
  {
    result.error = "correspondence options out of range (cell 1..1024, min_samples >= 1, fit_radius 0..64, "
                   "finite plane_z and outlier_tolerance >= 0)";
    return result;
  }
  const int rows = decoded.projector.rows, cols = decoded.projector.cols;
  if ((camera.width != 0 || camera.height != 0) && (int(camera.width) != cols || int(camera.height) != rows))
  {
    result.error = "camera calibration is " + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                   " but the captures are " + std::to_string(cols) + "x" + std::to_string(rows);
    return result;
  }
  result.error = cameraLensProblem(camera);
  if (!result.error.empty())
  {
    return result;
  }

  const int column_bits = grayCodeBits(projector_width), row_bits = grayCodeBits(projector_height);
  Grid grid;
  grid.cell = options.cell;
  grid.cells_x = (projector_width + options.cell - 1) / options.cell;
  grid.cells_y = (projector_height + options.cell - 1) / options.cell;
  const std::size_t cell_count = std::size_t(grid.cells_x) * std::size_t(grid.cells_y);
  const double origin_x = 0.5 * cols, origin_y = 0.5 * rows;

  // The cells' own decoded pixels (blocks no wider than a cell): support and camera spot.
  std::vector<Sums> own_u(cell_count), own_v(cell_count);
  for (int y = 0; y < rows; ++y)
  {
    const cv::Vec2f* projector = decoded.projector.ptr<cv::Vec2f>(y);
    const cv::Vec2b* bits = decoded.bits.ptr<cv::Vec2b>(y);
    for (int x = 0; x < cols; ++x)
    {
      const float u = projector[x][0], v = projector[x][1];
      if (!std::isfinite(u) || !std::isfinite(v) || bits[x][0] == 0 || bits[x][1] == 0 ||
          bits[x][0] > column_bits || bits[x][1] > row_bits || grayBlockWidth(column_bits, bits[x][0]) > options.cell ||
          grayBlockWidth(row_bits, bits[x][1]) > options.cell || u < 0.0f || v < 0.0f ||
          u > float(projector_width - 1) || v > float(projector_height - 1))
      {
        continue;
      }
      const std::size_t c = grid.of(u, v);
      own_u[c].add(x - origin_x, y - origin_y, u);
      own_v[c].add(x - origin_x, y - origin_y, v);
      ++result.samples;
    }
  }

  // Edge fits, twice: the second time without the edges off the first fit.
  std::vector<std::size_t> edge_cell(decoded.edges.size());
  std::vector<bool> edge_used(decoded.edges.size(), false);
  for (std::size_t i = 0; i < decoded.edges.size(); ++i)
  {
    const StripeEdge& e = decoded.edges[i];
    if (!std::isfinite(e.x) || !std::isfinite(e.y) || !std::isfinite(e.coordinate) || !std::isfinite(e.other) ||
        e.axis > 1)
    {
      continue;
    }
    edge_cell[i] = e.axis == 0 ? grid.of(e.coordinate, e.other) : grid.of(e.other, e.coordinate);
    edge_used[i] = true;
  }
  std::vector<Sums> edge_sums[2] = {std::vector<Sums>(cell_count), std::vector<Sums>(cell_count)};
  for (int pass = 0; pass < 2 && options.fit_radius > 0; ++pass)
  {
    for (std::vector<Sums>& sums : edge_sums)
    {
      std::fill(sums.begin(), sums.end(), Sums());
    }
    for (std::size_t i = 0; i < decoded.edges.size(); ++i)
    {
      if (edge_used[i])
      {
        const StripeEdge& e = decoded.edges[i];
        edge_sums[e.axis][edge_cell[i]].add(e.x - origin_x, e.y - origin_y, e.coordinate);
      }
    }
    if (pass == 1)
    {
      break;
    }
    std::vector<Affine> fits[2] = {std::vector<Affine>(cell_count), std::vector<Affine>(cell_count)};
    std::vector<bool> fitted[2] = {std::vector<bool>(cell_count, false), std::vector<bool>(cell_count, false)};
    for (int axis = 0; axis < 2; ++axis)
    {
      for (std::size_t c = 0; c < cell_count; ++c)
      {
        if (edge_sums[axis][c].n > 0)
        {
          fitted[axis][c] = fitAffine(windowSums(edge_sums[axis], grid, c, options.fit_radius), fits[axis][c]);
        }
      }
    }
    for (std::size_t i = 0; i < decoded.edges.size(); ++i)
    {
      const StripeEdge& e = decoded.edges[i];
      if (edge_used[i] && fitted[e.axis][edge_cell[i]] &&
          std::abs(fits[e.axis][edge_cell[i]].at(e.x - origin_x, e.y - origin_y) - e.coordinate) >
              options.outlier_tolerance)
      {
        edge_used[i] = false;
        ++result.rejected;
      }
    }
  }

  // Per cell with enough support: the camera point of the cell centre (fit) or the plain averages.
  std::vector<Vec2> camera_points, projector_points;
  std::vector<std::size_t> cells;
  for (std::size_t c = 0; c < cell_count; ++c)
  {
    if (own_u[c].n < options.min_samples)
    {
      continue;
    }
    const double mean_x = own_u[c].x / own_u[c].n, mean_y = own_u[c].y / own_u[c].n;
    Vec2 camera_point{mean_x, mean_y};
    Vec2 projector_point{own_u[c].t / own_u[c].n, own_v[c].t / own_v[c].n};
    if (options.fit_radius > 0)
    {
      Affine fu, fv;
      if (!fitAffine(windowSums(edge_sums[0], grid, c, options.fit_radius), fu) ||
          !fitAffine(windowSums(edge_sums[1], grid, c, options.fit_radius), fv))
      {
        continue;
      }
      const int cx = int(c % std::size_t(grid.cells_x)), cy = int(c / std::size_t(grid.cells_x));
      projector_point.x = 0.5 * (cx * options.cell + std::min((cx + 1) * options.cell, projector_width) - 1);
      projector_point.y = 0.5 * (cy * options.cell + std::min((cy + 1) * options.cell, projector_height) - 1);
      // Solve fu(x, y) = u, fv(x, y) = v for the camera point.
      const double det = fu.a * fv.b - fu.b * fv.a;
      if (!(std::abs(det) > 1e-12))
      {
        continue;
      }
      const double ru = projector_point.x - fu.at(mean_x, mean_y), rv = projector_point.y - fv.at(mean_x, mean_y);
      camera_point.x = mean_x + (fv.b * ru - fu.b * rv) / det;
      camera_point.y = mean_y + (fu.a * rv - fv.a * ru) / det;
      // The cell's own pixels are where the camera sees it: a fit that puts it far away is wrong.
      if (std::hypot(camera_point.x - mean_x, camera_point.y - mean_y) > 4.0)
      {
        continue;
      }
    }
    camera_points.push_back({camera_point.x + origin_x, camera_point.y + origin_y});
    projector_points.push_back(projector_point);
    cells.push_back(c);
  }
  const std::vector<Vec3> floor =
      options.plane ? cameraPixelsOnPlane(camera, base_T_camera_optical, camera_points, *options.plane, result.error)
                    : cameraPixelsOnPlane(camera, base_T_camera_optical, camera_points, options.plane_z, result.error);
  if (!result.error.empty())
  {
    return result;
  }
  for (std::size_t i = 0; i < cells.size(); ++i)
  {
    if (!isFinite(floor[i]))
    {
      continue;  // the camera sees this cell above the horizon: not on the floor
    }
    FloorPoint point;
    point.id = int(cells[i]);
    point.pixel = projector_points[i];
    point.world = floor[i];
    result.points.push_back(point);
  }
  result.coverage = double(result.points.size()) / double(cell_count);
  return result;
}
}  // namespace rviz_projector
