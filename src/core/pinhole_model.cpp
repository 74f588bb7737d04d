#include "rviz_projector/core/pinhole_model.h"

#include "rviz_projector/core/lens_distortion.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace rviz_projector
{
namespace
{
template <std::size_t N>
bool allZero(const std::array<double, N>& values)
{
  return std::all_of(values.begin(), values.end(), [](double v) { return v == 0.0; });
}

template <typename Container>
int firstNonFinite(const Container& values)
{
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    if (!std::isfinite(values[i]))
    {
      return static_cast<int>(i);
    }
  }
  return -1;
}
}  // namespace

PinholeModel::PinholeModel(std::uint32_t width, std::uint32_t height, double fx, double fy, double cx,
                           double cy, double tx, double ty)
  : width_(width), height_(height), fx_(fx), fy_(fy), cx_(cx), cy_(cy), tx_(tx), ty_(ty)
{
}

LensCheck PinholeModel::fromCalibration(const LensCalibration& c, PinholeModel& out)
{
  LensCheck check;
  std::ostringstream error;
  if (c.width == 0 || c.height == 0)
  {
    error << "image size is " << c.width << "x" << c.height << " (width and height must be > 0)";
    check.error = error.str();
    return check;
  }
  const bool use_k = allZero(c.P);
  if (use_k && allZero(c.K))
  {
    check.error = "P and K are all zero (uncalibrated)";
    return check;
  }
  const int bad_p = firstNonFinite(c.P);
  const int bad_k = firstNonFinite(c.K);
  if (!use_k && bad_p >= 0)
  {
    error << "P[" << bad_p << "] is not finite";
  }
  else if (use_k && bad_k >= 0)
  {
    error << "K[" << bad_k << "] is not finite";
  }
  else if (firstNonFinite(c.D) >= 0)
  {
    error << "D[" << firstNonFinite(c.D) << "] is not finite";
  }
  if (!error.str().empty())
  {
    check.error = error.str();
    return check;
  }
  double fx = use_k ? c.K[0] : c.P[0];
  double fy = use_k ? c.K[4] : c.P[5];
  double cx = use_k ? c.K[2] : c.P[2];
  double cy = use_k ? c.K[5] : c.P[6];
  double tx = use_k ? 0.0 : c.P[3];
  double ty = use_k ? 0.0 : c.P[7];
  const char* source = use_k ? "K" : "P";
  if (!(fx > 0.0) || !(fy > 0.0))
  {
    error << "focal length in " << source << " is not positive (fx = " << fx << ", fy = " << fy << ")";
    check.error = error.str();
    return check;
  }

  std::uint32_t width = c.width;
  std::uint32_t height = c.height;
  if (c.roi_width > 0 && c.roi_height > 0)
  {
    if (std::uint64_t(c.roi_x_offset) + c.roi_width > c.width ||
        std::uint64_t(c.roi_y_offset) + c.roi_height > c.height)
    {
      error << "region of interest " << c.roi_width << "x" << c.roi_height << "+" << c.roi_x_offset << "+"
            << c.roi_y_offset << " lies outside the " << c.width << "x" << c.height << " image";
      check.error = error.str();
      return check;
    }
    width = c.roi_width;
    height = c.roi_height;
    cx -= c.roi_x_offset;
    cy -= c.roi_y_offset;
  }
  const double bx = std::max<std::uint32_t>(c.binning_x, 1);
  const double by = std::max<std::uint32_t>(c.binning_y, 1);
  width = static_cast<std::uint32_t>(width / bx);
  height = static_cast<std::uint32_t>(height / by);
  if (width == 0 || height == 0)
  {
    error << "binning " << bx << "x" << by << " leaves no pixels";
    check.error = error.str();
    return check;
  }
  if (width > kMaxResolution || height > kMaxResolution)
  {
    error << "image size " << width << "x" << height << " exceeds the " << kMaxResolution << "x" << kMaxResolution
          << " limit";
    check.error = error.str();
    return check;
  }
  // Binning divides P's first row by binning_x and its second by binning_y (fx, cx, Tx; fy, cy, Ty),
  // after the ROI offset moved the principal point: u_binned = u_roi / b. That is CameraInfo's
  // definition as image_geometry::PinholeCameraModel implements it, so that a consumer of the same
  // CameraInfo puts a point on the same pixel; it is not (u + 0.5) / b - 0.5, which would keep the
  // centre of a binned pixel at the centre of the b x b pixels it sums, a quarter pixel apart at b = 2.
  fx /= bx;
  fy /= by;
  if (!(fx >= kMinFocalLength) || !(fy >= kMinFocalLength))
  {
    error << "focal length is below " << kMinFocalLength << " pixels" << (bx > 1 || by > 1 ? " after binning" : "")
          << " (fx = " << fx << ", fy = " << fy << ")";
    check.error = error.str();
    return check;
  }
  tx /= bx;
  ty /= by;
  cx /= bx;
  cy /= by;

  // A D that folds back inside K's raw image (the pixels the lens really lights) is refused.
  LensDistortion distortion;
  if (LensDistortion::fromCalibration(c, distortion).ok() && !distortion.none() && !allZero(c.K))
  {
    PinholeModel raw_lens;
    if (rawFromCalibration(c, raw_lens).ok())
    {
      const double corner = raw_lens.cornerRadius();
      const std::string fold = LensDistortion::foldError(distortion.foldCheck(corner), corner);
      if (!fold.empty())
      {
        check.error = fold;
        return check;
      }
    }
  }

  // A D that LensDistortion models (plumb_bob, rational_polynomial) is drawn by the ProjectorCamera
  // (issue 24); any other (equidistant, an unknown model) is not, and the view is the ideal pinhole.
  std::ostringstream warning;
  LensDistortion modelled;
  const bool distorted = std::any_of(c.D.begin(), c.D.end(), [](double d) { return d != 0.0; }) &&
                         !(LensDistortion::fromCalibration(c, modelled).ok() && !modelled.none());
  if (distorted)
  {
    warning << "distortion D is not applied (the view uses the ideal pinhole of " << source << ")";
  }
  const std::string& model = c.distortion_model;
  if (!model.empty() && model != "plumb_bob" && model != "rational_polynomial" && model != "equidistant")
  {
    warning << (distorted ? "; " : "") << "unknown distortion_model '" << model << "' (ignored)";
  }
  check.warning = warning.str();
  out = PinholeModel(width, height, fx, fy, cx, cy, tx, ty);
  return check;
}

bool PinholeModel::project(const Vec3& p, Vec2& pixel) const
{
  if (!(p.z > 0.0))
  {
    return false;
  }
  pixel.x = (fx_ * p.x + cx_ * p.z + tx_) / p.z;
  pixel.y = (fy_ * p.y + cy_ * p.z + ty_) / p.z;
  return std::isfinite(pixel.x) && std::isfinite(pixel.y);
}

Vec3 PinholeModel::ray(const Vec2& pixel) const
{
  return {(pixel.x - cx_) / fx_, (pixel.y - cy_) / fy_, 1.0};
}

double PinholeModel::cornerRadius() const
{
  double radius = 0.0;
  for (const double u : {-0.5, double(width_) - 0.5})
  {
    for (const double v : {-0.5, double(height_) - 0.5})
    {
      const Vec3 r = ray({u, v});
      radius = std::max(radius, std::hypot(r.x, r.y));
    }
  }
  return radius;
}

Vec3 PinholeModel::centre() const
{
  return {-tx_ / fx_, -ty_ / fy_, 0.0};
}

std::array<double, 16> PinholeModel::glProjectionMatrix(double near_clip, double far_clip) const
{
  const double w = width_;
  const double h = height_;
  const double depth = far_clip - near_clip;
  // OpenGL window coordinates put pixel centres at +0.5 (x right, y up); OpenCV at integers
  // (v down): x_gl = u + 0.5, y_gl = h - (v + 0.5). Written out for clip space with w = -z_gl.
  return {2.0 * fx_ / w, 0.0, 1.0 - 2.0 * (cx_ + 0.5) / w, 2.0 * tx_ / w,
          0.0, 2.0 * fy_ / h, 2.0 * (cy_ + 0.5) / h - 1.0, -2.0 * ty_ / h,
          0.0, 0.0, -(far_clip + near_clip) / depth, -2.0 * far_clip * near_clip / depth,
          0.0, 0.0, -1.0, 0.0};
}
LensCheck PinholeModel::rawFromCalibration(const LensCalibration& calibration, PinholeModel& out)
{
  LensCalibration raw = calibration;
  raw.P.fill(0.0);
  raw.D.clear();
  return fromCalibration(raw, out);
}
}  // namespace rviz_projector
