// A lens's distortion as a CameraInfo gives it (D, distortion_model): OpenCV's model, as
// image_geometry and cv::projectPoints use it. For a projector, a pixel's ray is the undistorted
// direction of that pixel: ideal (pinhole) normalised coordinates -> distort() -> the normalised
// coordinates of the raw pixel that lights that ray (through K).
//
// Models: "plumb_bob" (k1, k2, p1, p2[, k3]: 4 or 5 values) and "rational_polynomial" (k1, k2, p1, p2,
// k3, k4, k5, k6: 8 values). D all zero (or empty) is no distortion whatever the model says.
// The maths is OpenCV's (cv::projectPoints, cv::undistortPoints); this class adds what OpenCV does
// not check: whether the radial map folds back before the image corner (foldCheck).
#pragma once

#include <string>
#include <vector>

#include "rviz_projector/core/lens_calibration.h"
#include "rviz_projector/core/lens_check.h"
#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
class LensDistortion
{
public:
  enum class Model
  {
    None,
    PlumbBob,
    RationalPolynomial,
  };

  /// No distortion.
  LensDistortion() = default;
  /// `coefficients` in OpenCV's order (k1, k2, p1, p2, k3[, k4, k5, k6]); all zero makes Model::None.
  LensDistortion(Model model, std::vector<double> coefficients);

  /**
   * From a CameraInfo's distortion_model and D. Errors: a D that is not finite, a D whose length
   * the model does not take. An empty or unknown model with a non-zero D is an error too (nothing
   * says how to apply it); D all zero is no distortion with any model name. On error `out` is
   * left unchanged.
   */
  static LensCheck fromCalibration(const LensCalibration& calibration, LensDistortion& out);

  Model model() const { return model_; }
  bool none() const { return model_ == Model::None; }
  /// OpenCV's order, 5 (plumb_bob) or 8 (rational_polynomial) values; empty for none.
  const std::vector<double>& coefficients() const { return coefficients_; }

  /// Distorted normalised coordinates of ideal normalised ones (z = 1).
  std::vector<Vec2> distort(const std::vector<Vec2>& ideal) const;
  /// Ideal normalised coordinates of distorted ones (OpenCV's iteration, run to 1e-12 or 200
  /// steps). Only meaningful where foldCheck() found the map monotonic.
  std::vector<Vec2> undistort(const std::vector<Vec2>& distorted) const;

  /// The radial map without tangential terms: the distorted radius of an ideal radius r.
  double radialMap(double r) const;

  struct Fold
  {
    bool folds = false;
    double ideal_radius = 0.0;      ///< where the radial map stops increasing (folds)
    double distorted_radius = 0.0;  ///< its distorted radius (the largest the lens reaches)
  };
  /**
   * Whether the radial map r -> radialMap(r) increases all the way until it reaches
   * `distorted_radius` (the image corner's normalised radius): a lens whose map turns back (or
   * whose rational denominator reaches zero) before that shows two rays on one pixel, or none:
   * such a D cannot be drawn. Tangential terms are not considered (they are small in any real fit).
   */
  Fold foldCheck(double distorted_radius) const;

  /// The check as a sentence for the user ("" when the map does not fold).
  static std::string foldError(const Fold& fold, double corner_radius);

private:
  Model model_ = Model::None;
  std::vector<double> coefficients_;
};

/// "plumb_bob", "rational_polynomial" or "none".
const char* modelName(LensDistortion::Model model);
}  // namespace rviz_projector
