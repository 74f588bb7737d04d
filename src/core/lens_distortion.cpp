#include "rviz_projector/core/lens_distortion.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <utility>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

namespace rviz_projector
{
namespace
{
constexpr std::size_t kPlumbBobSize = 5;
constexpr std::size_t kRationalSize = 8;
/// The fold scan: steps of this ideal radius up to kFineRange, coarser after.
constexpr double kFineStep = 1e-4;
constexpr double kFineRange = 3.0;  // 71.6 deg off axis
constexpr double kMaxRadius = 60.0;  // 89 deg off axis: a lens that has not reached its corner here never does

std::vector<cv::Point2d> toCv(const std::vector<Vec2>& points)
{
  std::vector<cv::Point2d> out;
  out.reserve(points.size());
  for (const Vec2& p : points)
  {
    out.emplace_back(p.x, p.y);
  }
  return out;
}

std::vector<Vec2> fromCv(const std::vector<cv::Point2d>& points)
{
  std::vector<Vec2> out;
  out.reserve(points.size());
  for (const cv::Point2d& p : points)
  {
    out.push_back({p.x, p.y});
  }
  return out;
}
}  // namespace

LensDistortion::LensDistortion(Model model, std::vector<double> coefficients)
  : model_(model), coefficients_(std::move(coefficients))
{
  const std::size_t size = model_ == Model::RationalPolynomial ? kRationalSize : kPlumbBobSize;
  coefficients_.resize(model_ == Model::None ? 0 : size, 0.0);
  if (std::all_of(coefficients_.begin(), coefficients_.end(), [](double d) { return d == 0.0; }))
  {
    model_ = Model::None;
    coefficients_.clear();
  }
}

LensCheck LensDistortion::fromCalibration(const LensCalibration& c, LensDistortion& out)
{
  LensCheck check;
  for (std::size_t i = 0; i < c.D.size(); ++i)
  {
    if (!std::isfinite(c.D[i]))
    {
      check.error = "D[" + std::to_string(i) + "] is not finite";
      return check;
    }
  }
  if (std::all_of(c.D.begin(), c.D.end(), [](double d) { return d == 0.0; }))
  {
    out = LensDistortion();
    return check;
  }
  std::ostringstream error;
  if (c.distortion_model == "plumb_bob")
  {
    if (c.D.size() != 4 && c.D.size() != kPlumbBobSize)
    {
      error << "D has " << c.D.size() << " values: plumb_bob takes 5 (k1, k2, p1, p2, k3)";
    }
  }
  else if (c.distortion_model == "rational_polynomial")
  {
    if (c.D.size() != kRationalSize)
    {
      error << "D has " << c.D.size() << " values: rational_polynomial takes 8 (k1, k2, p1, p2, k3, k4, k5, k6)";
    }
  }
  else
  {
    error << "distortion_model '" << c.distortion_model
          << "' with a non-zero D: only plumb_bob and rational_polynomial can be drawn";
  }
  if (!error.str().empty())
  {
    check.error = error.str();
    return check;
  }
  out = LensDistortion(c.distortion_model == "plumb_bob" ? Model::PlumbBob : Model::RationalPolynomial, c.D);
  return check;
}

std::vector<Vec2> LensDistortion::distort(const std::vector<Vec2>& ideal) const
{
  if (none() || ideal.empty())
  {
    return ideal;
  }
  std::vector<cv::Point3d> rays;
  rays.reserve(ideal.size());
  for (const Vec2& p : ideal)
  {
    rays.emplace_back(p.x, p.y, 1.0);
  }
  std::vector<cv::Point2d> out;
  const cv::Matx33d identity = cv::Matx33d::eye();
  cv::projectPoints(rays, cv::Vec3d(0.0, 0.0, 0.0), cv::Vec3d(0.0, 0.0, 0.0), identity, coefficients_, out);
  return fromCv(out);
}

std::vector<Vec2> LensDistortion::undistort(const std::vector<Vec2>& distorted) const
{
  if (none() || distorted.empty())
  {
    return distorted;
  }
  std::vector<cv::Point2d> out;
  const cv::Matx33d identity = cv::Matx33d::eye();
  cv::undistortPoints(toCv(distorted), out, identity, coefficients_, cv::noArray(), cv::noArray(),
                      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-12));
  return fromCv(out);
}

double LensDistortion::radialMap(double r) const
{
  if (none())
  {
    return r;
  }
  const std::vector<double>& k = coefficients_;
  const double r2 = r * r;
  const double numerator = 1.0 + r2 * (k[0] + r2 * (k[1] + r2 * k[4]));
  const double denominator =
      model_ == Model::RationalPolynomial ? 1.0 + r2 * (k[5] + r2 * (k[6] + r2 * k[7])) : 1.0;
  return r * numerator / denominator;
}

LensDistortion::Fold LensDistortion::foldCheck(double distorted_radius) const
{
  Fold fold;
  if (none())
  {
    return fold;
  }
  const std::vector<double>& k = coefficients_;
  const auto denominator = [&](double r) {
    const double r2 = r * r;
    return model_ == Model::RationalPolynomial ? 1.0 + r2 * (k[5] + r2 * (k[6] + r2 * k[7])) : 1.0;
  };
  double r = 0.0;
  double g = 0.0;
  while (g < distorted_radius)
  {
    const double step = r < kFineRange ? kFineStep : r * kFineStep;
    const double next_r = r + step;
    const double next_g = radialMap(next_r);
    if (!(denominator(next_r) > 0.0) || !(next_g > g) || next_r > kMaxRadius)
    {
      fold.folds = true;
      fold.ideal_radius = r;
      fold.distorted_radius = g;
      return fold;
    }
    r = next_r;
    g = next_g;
  }
  return fold;
}

std::string LensDistortion::foldError(const Fold& fold, double corner_radius)
{
  if (!fold.folds)
  {
    return std::string();
  }
  std::ostringstream text;
  text << std::fixed << std::setprecision(3) << "distortion D folds back at the normalised radius r = "
       << fold.ideal_radius << " (where it reaches " << fold.distorted_radius
       << "), inside the image (its corner is at " << corner_radius
       << "): pixels beyond would show two rays or none; refused, nothing is drawn";
  return text.str();
}

const char* modelName(LensDistortion::Model model)
{
  switch (model)
  {
    case LensDistortion::Model::PlumbBob:
      return "plumb_bob";
    case LensDistortion::Model::RationalPolynomial:
      return "rational_polynomial";
    case LensDistortion::Model::None:
      break;
  }
  return "none";
}
}  // namespace rviz_projector
