// The projector as an ideal pinhole: pixels <-> rays, and the matching OpenGL projection matrix.
#pragma once

#include <array>
#include <cstdint>

#include "rviz_projector/core/lens_calibration.h"
#include "rviz_projector/core/lens_check.h"
#include "rviz_projector/core/vec2.h"
#include "rviz_projector/core/vec3.h"

namespace rviz_projector
{
/**
 * Pixel convention is ROS/OpenCV's: pixel (u, v) has its centre at integer coordinates, u right,
 * v down, (0, 0) is the centre of the top-left pixel. Points are in the optical frame: x right,
 * y down, z forward. Projection follows CameraInfo's P:  u = (fx x + cx z + Tx) / z,
 * v = (fy y + cy z + Ty) / z.
 */
class PinholeModel
{
public:
  /// Largest width or height accepted (beyond it no render target is allocated).
  static constexpr std::uint32_t kMaxResolution = 16384;
  /// Smallest focal length accepted, pixels (smaller ones make rays and the projection blow up).
  static constexpr double kMinFocalLength = 1e-3;

  PinholeModel() = default;
  PinholeModel(std::uint32_t width, std::uint32_t height, double fx, double fy, double cx, double cy,
               double tx = 0.0, double ty = 0.0);

  /**
   * Builds the model as CameraInfo defines it, exactly as image_geometry::PinholeCameraModel does:
   * from P (from [K | 0] when P is all zero), then the region of interest (its offset subtracted
   * from cx, cy) and binning (P's rows divided by binning_x, binning_y) applied. The model's image
   * is the reduced one: the ROI's size (the whole image when the ROI is empty) divided by the
   * binning, rounded down. On error `out` is left unchanged.
   *
   * A non-zero D (plumb_bob, rational_polynomial) whose radial map folds back before the image
   * corner of K's raw image is an error (LensDistortion::foldCheck): such a lens cannot be drawn.
   */
  static LensCheck fromCalibration(const LensCalibration& calibration, PinholeModel& out);
  /// The pinhole of K alone (P taken as all zero, D ignored; ROI and binning applied as above): the
  /// raw pixels of a distorting lens, which a projector draws through (it has no rectified image).
  static LensCheck rawFromCalibration(const LensCalibration& calibration, PinholeModel& out);

  /// Pixel of a point in the optical frame; false when the point is not in front of the lens.
  bool project(const Vec3& point, Vec2& pixel) const;
  /// Direction (z = 1) of the ray through a pixel, from the optical centre.
  Vec3 ray(const Vec2& pixel) const;
  /// Optical centre in the optical frame (non-zero only with Tx/Ty set).
  Vec3 centre() const;
  /// Largest normalised radius, |ray(pixel).xy|, of the image's four outer corners (pixel edges).
  double cornerRadius() const;

  /**
   * Row-major 4x4 projection matrix for an OpenGL-style camera (x right, y up, looking down -z)
   * that puts a point on exactly the pixel project() predicts, with OpenGL's pixel centres at +0.5.
   */
  std::array<double, 16> glProjectionMatrix(double near_clip, double far_clip) const;

  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }
  double fx() const { return fx_; }
  double fy() const { return fy_; }
  double cx() const { return cx_; }
  double cy() const { return cy_; }
  double tx() const { return tx_; }
  double ty() const { return ty_; }

private:
  std::uint32_t width_ = 0;
  std::uint32_t height_ = 0;
  double fx_ = 1.0;
  double fy_ = 1.0;
  double cx_ = 0.0;
  double cy_ = 0.0;
  double tx_ = 0.0;
  double ty_ = 0.0;
};
}  // namespace rviz_projector
