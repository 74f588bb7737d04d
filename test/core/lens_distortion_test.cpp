// LensDistortion and WarpGrid (issue 24): OpenCV's distortion model, the fold check, and the warp
// grid that draws an ideal render through the lens. The oracle is the model's formula written out
// here (Brown-Conrady radial + tangential, OpenCV's rational form), independent of OpenCV, which the
// code under test calls; fold radii are computed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "rviz_projector/core/lens_distortion.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/warp_grid.h"

using rviz_projector::LensCalibration;
using rviz_projector::LensDistortion;
using rviz_projector::PinholeModel;
using rviz_projector::Vec2;
using rviz_projector::WarpGrid;

namespace
{
using Model = LensDistortion::Model;

/// The distortion formula (k1, k2, p1, p2, k3[, k4, k5, k6]) of a normalised ideal point.
Vec2 oracleDistort(const std::vector<double>& d, const Vec2& p)
{
  std::vector<double> k = d;
  k.resize(8, 0.0);
  const double r2 = p.x * p.x + p.y * p.y;
  const double radial = (1 + k[0] * r2 + k[1] * r2 * r2 + k[4] * r2 * r2 * r2) /
                        (1 + k[5] * r2 + k[6] * r2 * r2 + k[7] * r2 * r2 * r2);
  return {p.x * radial + 2 * k[2] * p.x * p.y + k[3] * (r2 + 2 * p.x * p.x),
          p.y * radial + k[2] * (r2 + 2 * p.y * p.y) + 2 * k[3] * p.x * p.y};
}

/// The lenses, on its 1280x800 projector with f = 1900.
const std::vector<double> kBarrel{-0.05, 0, 0, 0, 0};
const std::vector<double> kPincushion{0.10, 0, 0, 0, 0};
const std::vector<double> kWide{-0.2, 0.05, 0, 0, 0};
const PinholeModel kLens(1280, 800, 1900.0, 1900.0, 639.5, 399.5);

std::vector<Vec2> imagePoints()
{
  std::vector<Vec2> points;
  for (double x = -0.35; x <= 0.35; x += 0.05)
  {
    for (double y = -0.22; y <= 0.22; y += 0.04)
    {
      points.push_back({x, y});
    }
  }
  return points;
}

LensCalibration calibration(const std::string& model, const std::vector<double>& d)
{
  LensCalibration c;
  c.width = 1280;
  c.height = 800;
  c.K = {1900, 0, 639.5, 0, 1900, 399.5, 0, 0, 1};
  c.P = {1900, 0, 639.5, 0, 0, 1900, 399.5, 0, 0, 0, 1, 0};
  c.distortion_model = model;
  c.D = d;
  return c;
}
}  // namespace

TEST(LensDistortion, DistortFollowsTheFormulaForBothModels)
{
  const LensDistortion plumb(Model::PlumbBob, {-0.21, 0.06, 0.0012, -0.0009, -0.01});
  const LensDistortion rational(Model::RationalPolynomial, {0.3, -0.1, 0.001, 0.002, 0.02, 0.5, -0.05, 0.01});
  const std::vector<Vec2> ideal = imagePoints();
  for (const LensDistortion* lens : {&plumb, &rational})
  {
    const std::vector<Vec2> out = lens->distort(ideal);
    ASSERT_EQ(out.size(), ideal.size());
    for (std::size_t i = 0; i < ideal.size(); ++i)
    {
      const Vec2 expected = oracleDistort(lens->coefficients(), ideal[i]);
      EXPECT_NEAR(out[i].x, expected.x, 1e-12) << rviz_projector::modelName(lens->model()) << " point " << i;
      EXPECT_NEAR(out[i].y, expected.y, 1e-12) << rviz_projector::modelName(lens->model()) << " point " << i;
    }
  }
}

TEST(LensDistortion, UndistortGivesTheRayThatTheFormulaSendsToThePixel)
{
  for (const std::vector<double>& d : {kBarrel, kPincushion, kWide, std::vector<double>{-0.2, 0.05, 0.001, -0.002, 0.0}})
  {
    const LensDistortion lens(Model::PlumbBob, d);
    std::vector<Vec2> distorted;
    for (const Vec2& p : imagePoints())
    {
      distorted.push_back(p);  // the pixels of the image (normalised)
    }
    const std::vector<Vec2> rays = lens.undistort(distorted);
    for (std::size_t i = 0; i < rays.size(); ++i)
    {
      const Vec2 back = oracleDistort(d, rays[i]);
      EXPECT_NEAR(back.x, distorted[i].x, 1e-10) << "k1 " << d[0] << " point " << i;
      EXPECT_NEAR(back.y, distorted[i].y, 1e-10) << "k1 " << d[0] << " point " << i;
    }
  }
}

TEST(LensDistortion, FromCalibrationTakesTheModelsAndRefusesWhatCannotBeDrawn)
{
  LensDistortion d;
  EXPECT_TRUE(LensDistortion::fromCalibration(calibration("plumb_bob", {0, 0, 0, 0, 0}), d).ok());
  EXPECT_TRUE(d.none());
  EXPECT_TRUE(LensDistortion::fromCalibration(calibration("", {}), d).ok()) << "no D: no distortion";
  EXPECT_TRUE(LensDistortion::fromCalibration(calibration("equidistant", {0, 0, 0, 0}), d).ok())
      << "any model with D all zero is no distortion";
  EXPECT_TRUE(d.none());

  ASSERT_TRUE(LensDistortion::fromCalibration(calibration("plumb_bob", {-0.05, 0.01, 0, 0}), d).ok())
      << "4 values: k3 = 0";
  EXPECT_EQ(d.model(), Model::PlumbBob);
  EXPECT_EQ(d.coefficients(), (std::vector<double>{-0.05, 0.01, 0, 0, 0}));
  ASSERT_TRUE(LensDistortion::fromCalibration(calibration("rational_polynomial", {0.1, 0, 0, 0, 0, 0.2, 0, 0}), d).ok());
  EXPECT_EQ(d.model(), Model::RationalPolynomial);

  const LensDistortion before = d;
  const auto error = [&](const LensCalibration& c) { return LensDistortion::fromCalibration(c, d).error; };
  EXPECT_NE(error(calibration("plumb_bob", {-0.05, 0.01, 0})).find("D has 3 values: plumb_bob takes 5"), std::string::npos);
  EXPECT_NE(error(calibration("rational_polynomial", {-0.05, 0, 0, 0, 0})).find("rational_polynomial takes 8"),
            std::string::npos);
  EXPECT_NE(error(calibration("equidistant", {0.1, 0, 0, 0})).find("'equidistant' with a non-zero D"), std::string::npos);
  EXPECT_NE(error(calibration("plumb_bob", {std::nan(""), 0, 0, 0, 0})).find("D[0] is not finite"), std::string::npos);
  EXPECT_EQ(d.coefficients(), before.coefficients()) << "left unchanged on error";
}

TEST(LensDistortion, AFittedK3ThatFoldsBackInsideTheImageIsFound)
{
  // g(r) = r (1 + k3 r^6): g'(r) = 1 + 7 k3 r^6 = 0 at r = (1 / 54.6)^(1/6) = 0.51341;
  // g there = 0.51341 (1 - 7.8 / 54.6) = 0.51341 * 6 / 7 = 0.44007 (by hand).
  const LensDistortion fitted(Model::PlumbBob, {0, 0, 0, 0, -7.8});
  const LensDistortion::Fold fold = fitted.foldCheck(0.566);
  EXPECT_TRUE(fold.folds);
  EXPECT_NEAR(fold.ideal_radius, 0.51341, 2e-4);
  EXPECT_NEAR(fold.distorted_radius, 0.44007, 2e-4);
  EXPECT_FALSE(fitted.foldCheck(0.40).folds) << "an image whose corner it reaches before folding";
  const std::string text = LensDistortion::foldError(fold, 0.566);
  EXPECT_NE(text.find("r = 0.513"), std::string::npos) << text;
  EXPECT_NE(text.find("corner is at 0.566"), std::string::npos) << text;
  // The lenses never fold on its projector (corner radius hypot(640, 400) / 1900 = 0.3972).
  EXPECT_NEAR(kLens.cornerRadius(), std::hypot(640.0, 400.0) / 1900.0, 1e-12);
  for (const std::vector<double>& d : {kBarrel, kPincushion, kWide})
  {
    EXPECT_FALSE(LensDistortion(Model::PlumbBob, d).foldCheck(kLens.cornerRadius()).folds) << "k1 " << d[0];
  }
  // Strong barrel: g(r) = r (1 - 0.5 r^2) peaks at r = sqrt(2/3) = 0.8165, g = 0.5443.
  const LensDistortion barrel(Model::PlumbBob, {-0.5, 0, 0, 0, 0});
  EXPECT_NEAR(barrel.foldCheck(0.6).ideal_radius, std::sqrt(2.0 / 3.0), 2e-4);
  EXPECT_FALSE(barrel.foldCheck(0.5).folds);
}

TEST(LensDistortion, PinholeModelRefusesALensThatFoldsNamingTheRadius)
{
  // 1280x800, f = 1100: corner radius hypot(640, 400) / 1100 = 0.6861 > 0.4401, the most the
  // k3 = -7.8 lens reaches.
  LensCalibration c = calibration("plumb_bob", {0, 0, 0, 0, -7.8});
  c.K = {1100, 0, 639.5, 0, 1100, 399.5, 0, 0, 1};
  c.P = {1100, 0, 639.5, 0, 0, 1100, 399.5, 0, 0, 0, 1, 0};
  PinholeModel lens;
  const auto check = PinholeModel::fromCalibration(c, lens);
  EXPECT_FALSE(check.ok());
  EXPECT_NE(check.error.find("folds back at the normalised radius r = 0.513"), std::string::npos) << check.error;
  EXPECT_EQ(lens.width(), 0u) << "left unchanged";
  // The same D on a narrow lens (f = 1900 * 2: corner radius 0.199) is no fold.
  c.K = {3800, 0, 639.5, 0, 3800, 399.5, 0, 0, 1};
  c.P = {3800, 0, 639.5, 0, 0, 3800, 399.5, 0, 0, 0, 1, 0};
  EXPECT_TRUE(PinholeModel::fromCalibration(c, lens).ok());
}

TEST(WarpGrid, VerticesSpanTheRawImageAndTheirRaysComeBackThroughTheFormula)
{
  for (const std::vector<double>& d : {kBarrel, kPincushion, kWide})
  {
    const LensDistortion lens(Model::PlumbBob, d);
    const WarpGrid grid = rviz_projector::makeWarpGrid(kLens, lens);
    ASSERT_EQ(grid.columns, 32u);
    ASSERT_EQ(grid.rows, 20u);
    ASSERT_EQ(grid.raw.size(), 33u * 21u);
    EXPECT_EQ(grid.raw.front().x, -0.5);
    EXPECT_EQ(grid.raw.front().y, -0.5);
    EXPECT_DOUBLE_EQ(grid.raw.back().x, 1279.5);
    EXPECT_DOUBLE_EQ(grid.raw.back().y, 799.5);
    const PinholeModel& ideal = grid.ideal_lens;
    for (std::size_t v = 0; v < grid.raw.size(); ++v)
    {
      // The ideal pixel's ray, distorted by the formula, lands on the raw vertex.
      const Vec2 ray{(grid.ideal[v].x - ideal.cx()) / ideal.fx(), (grid.ideal[v].y - ideal.cy()) / ideal.fy()};
      const Vec2 lit = oracleDistort(d, ray);
      EXPECT_NEAR(kLens.cx() + kLens.fx() * lit.x, grid.raw[v].x, 1e-6) << "k1 " << d[0] << " vertex " << v;
      EXPECT_NEAR(kLens.cy() + kLens.fy() * lit.y, grid.raw[v].y, 1e-6) << "k1 " << d[0] << " vertex " << v;
      // Inside the ideal image, at least half a pixel from its edges.
      EXPECT_GE(grid.ideal[v].x, 0.0);
      EXPECT_GE(grid.ideal[v].y, 0.0);
      EXPECT_LE(grid.ideal[v].x, ideal.width() - 1.0);
      EXPECT_LE(grid.ideal[v].y, ideal.height() - 1.0);
      const Vec2 t = grid.textureCoordinate(v);
      EXPECT_GT(t.x, 0.0);
      EXPECT_LT(t.x, 1.0);
    }
    if (d[0] < 0.0)
    {
      EXPECT_DOUBLE_EQ(ideal.fx(), 1900.0) << "a barrel lens squeezes the picture: no scaling";
      EXPECT_GT(ideal.width(), 1280u) << "a barrel lens reaches further: the ideal render is larger";
    }
    else
    {
      // A pincushion spreads its corners: x_d = x (1 + 0.1 r^2) grows dx_d/dx = 1 + 0.1 (r^2 + 2 x^2)
      // times as fast as x. In the corner cell (its middle at ideal x = 0.3216, y = 0.2074 by hand
      // from the corner's distorted (0.3368, 0.2105)) that is 1 + 0.1 (0.1464 + 0.2069) = 1.0353:
      // the ideal render is drawn that much sharper.
      EXPECT_NEAR(ideal.fx() / 1900.0, 1.0353, 0.002);
    }
  }
}

TEST(WarpGrid, InterpolationErrorIsWhatTheCellCountPromises)
{
  // Reference figures (doc: shared notes on distortion, measured independently): k1 = -0.05:
  // ~0.10 / 0.026 / 0.007 px for 16x10 / 32x20 / 64x40 cells; the wide lens 0.45 / 0.12 / 0.03 px.
  struct Case
  {
    std::vector<double> d;
    std::uint32_t columns, rows;
    double figure;
  };
  for (const Case& c : {Case{kBarrel, 16, 10, 0.10}, Case{kBarrel, 32, 20, 0.026}, Case{kBarrel, 64, 40, 0.007},
                        Case{kWide, 16, 10, 0.45}, Case{kWide, 32, 20, 0.12}, Case{kWide, 64, 40, 0.03}})
  {
    const LensDistortion lens(Model::PlumbBob, c.d);
    const WarpGrid grid = rviz_projector::makeWarpGrid(kLens, lens, c.columns, c.rows);
    const double error = rviz_projector::warpGridError(grid, kLens, lens, 6);
    EXPECT_LE(error, 1.35 * c.figure) << "k1 " << c.d[0] << ", " << c.columns << "x" << c.rows;
    EXPECT_GE(error, 0.5 * c.figure) << "k1 " << c.d[0] << ", " << c.columns << "x" << c.rows
                                     << ": far below the reference: is the error measured at all?";
  }
  // No distortion: the grid is exact.
  const LensDistortion none;
  EXPECT_LT(rviz_projector::warpGridError(rviz_projector::makeWarpGrid(kLens, none), kLens, none), 1e-9);
}
