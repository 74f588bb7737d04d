// ProjectorCamera's Test pattern = Crosshairs in rendered pixels (issue 12): the crosshairs land on
// the pixels the issue's rule gives (computed here by hand, not by the core), nothing else is lit,
// the picture depends on neither the mount nor tf nor the scene, rviz's main view never shows it;
// a full calibration round trip from the rendered pixels recovers the true mount; old configs'
// `Test pattern: true/false` load as Metric grid / Off.
//
// Centres are located from the rendered window: the connected white component around the expected
// centre is the cross (the digits are separate components); the x of its vertical arm and the y of
// its horizontal arm are the centroids of the pixels outside the other arm. Bound: 0.25 px.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <QColor>
#include <QImage>
#include <rviz/config.h>
#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/visualization_manager.h>
#include <rviz/yaml_config_reader.h>
#include <sensor_msgs/Image.h>

#include "rviz_projector/core/crosshair_pattern.h"
#include "rviz_projector/core/mount_solver.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output_window.h"
#include "projector_test_fixture.h"

using rviz_projector_test::bodyMount;
using rviz_projector_test::countColour;
using rviz_projector_test::Letterbox;
using rviz_projector_test::Mount;
using rviz_projector_test::PixelOracle;
using rviz_projector_test::ProjectorCameraTest;
using rviz_projector_test::projectorInfo;
using rviz_projector_test::RvizTest;
using rviz_projector_test::Status;
using rviz_projector_test::Vec2;

namespace
{
constexpr double kBound = 0.25;
const QRgb kWhite = qRgb(255, 255, 255);
const QRgb kGreen = qRgb(0, 255, 0);

/// The issue's rule, by hand: n centres spread evenly over the central 80% of an image `size`
/// pixels wide (its outer edges at -0.5 and size - 0.5), rounded to the nearest whole pixel, ties
/// up; a single one on the centre line. In integers: u = (-5 (n-1) + size (n-1) + 8 i size) / (10 (n-1)).
std::vector<int> handCentres(int size, int n)
{
  if (n == 1)
  {
    return {size / 2};  // (size - 1) / 2, a tie for even sizes, rounded up
  }
  std::vector<int> centres;
  const long den = 10L * (n - 1);
  for (int i = 0; i < n; ++i)
  {
    const long num = -5L * (n - 1) + long(size) * (n - 1) + 8L * i * size;
    centres.push_back(int((2 * num + den) / (2 * den)));  // floor(num / den + 1/2), num > 0
  }
  return centres;
}

/// Crosshair id -> pixel, row by row from the top-left, by hand.
std::vector<Vec2> handPattern(int width, int height, int rows, int cols)
{
  std::vector<Vec2> pixels;
  for (int v : handCentres(height, rows))
  {
    for (int u : handCentres(width, cols))
    {
      pixels.push_back(Vec2{double(u), double(v)});
    }
  }
  return pixels;
}

double brightness(QRgb c)
{
  return std::min({qRed(c), qGreen(c), qBlue(c)}) / 255.0;
}

/// The centre of the cross around `around` (window pixels, pixel centres at integers), see the
/// file comment. False when no white pixel is within 4 px of `around`.
bool crossCentre(const QImage& window, const Vec2& around, int reach, Vec2& centre)
{
  const int ax = int(std::lround(around.x)), ay = int(std::lround(around.y));
  const int x0 = std::max(0, ax - reach), x1 = std::min(window.width() - 1, ax + reach);
  const int y0 = std::max(0, ay - reach), y1 = std::min(window.height() - 1, ay + reach);
  if (x0 > x1 || y0 > y1)
  {
    return false;
  }
  const int w = x1 - x0 + 1, h = y1 - y0 + 1;
  auto lit = [&](int x, int y) { return brightness(window.pixel(x, y)) > 0.25; };
  // Seed: the lit pixel nearest to `around`.
  int sx = -1, sy = -1;
  double best = 4.0;
  for (int y = y0; y <= y1; ++y)
  {
    for (int x = x0; x <= x1; ++x)
    {
      const double d = std::hypot(x - around.x, y - around.y);
      if (d <= best && lit(x, y))
      {
        best = d;
        sx = x;
        sy = y;
      }
    }
  }
  if (sx < 0)
  {
    return false;
  }
  // Its 4-connected component within the box.
  std::vector<char> in(std::size_t(w) * h, 0);
  std::vector<std::pair<int, int>> stack{{sx, sy}}, component;
  in[std::size_t(sy - y0) * w + (sx - x0)] = 1;
  while (!stack.empty())
  {
    const auto p = stack.back();
    stack.pop_back();
    component.push_back(p);
    const int nx[] = {p.first + 1, p.first - 1, p.first, p.first};
    const int ny[] = {p.second, p.second, p.second + 1, p.second - 1};
    for (int k = 0; k < 4; ++k)
    {
      if (nx[k] < x0 || nx[k] > x1 || ny[k] < y0 || ny[k] > y1)
      {
        continue;
      }
      char& seen = in[std::size_t(ny[k] - y0) * w + (nx[k] - x0)];
      if (!seen && lit(nx[k], ny[k]))
      {
        seen = 1;
        stack.push_back({nx[k], ny[k]});
      }
    }
  }
  std::vector<int> row_count(h, 0), col_count(w, 0);
  for (const auto& p : component)
  {
    ++row_count[p.second - y0];
    ++col_count[p.first - x0];
  }
  const int max_row = *std::max_element(row_count.begin(), row_count.end());
  const int max_col = *std::max_element(col_count.begin(), col_count.end());
  // Vertical arm: pixels in rows the horizontal arm does not cross; and the other way round.
  double vx = 0, vw = 0, hy = 0, hw = 0;
  for (const auto& p : component)
  {
    const double b = brightness(window.pixel(p.first, p.second));
    if (2 * row_count[p.second - y0] < max_row)
    {
      vx += b * p.first;
      vw += b;
    }
    if (2 * col_count[p.first - x0] < max_col)
    {
      hy += b * p.second;
      hw += b;
    }
  }
  if (vw <= 0 || hw <= 0)
  {
    return false;
  }
  centre = Vec2{vx / vw, hy / hw};
  return true;
}

/// Window pixel (pixel-centre coordinates) -> image pixel, through the letterbox.
Vec2 toImage(const Letterbox& box, const PixelOracle& oracle, const Vec2& w)
{
  return Vec2{(w.x - box.left + 0.5) * oracle.imageWidth() / box.width - 0.5,
              (w.y - box.top + 0.5) * oracle.imageHeight() / box.height - 0.5};
}

/// Window pixels that are lit but lie outside every rectangle, and that lie inside one but are not
/// lit; window pixels straddling an image pixel's edge (non-integer scales) are not judged.
std::pair<int, int> litOutsideAndDarkInside(const QImage& window, const Letterbox& box, int iw, int ih,
                                            const std::vector<rviz_projector::PatternRect>& rects)
{
  std::vector<char> mask(std::size_t(iw) * ih, 0);
  for (const auto& r : rects)
  {
    for (int v = int(std::lround(r.y0 + 0.5)); v < int(std::lround(r.y1 + 0.5)); ++v)
    {
      for (int u = int(std::lround(r.x0 + 0.5)); u < int(std::lround(r.x1 + 0.5)); ++u)
      {
        if (u >= 0 && v >= 0 && u < iw && v < ih)
        {
          mask[std::size_t(v) * iw + u] = 1;
        }
      }
    }
  }
  int outside = 0, inside = 0;
  const double sx = double(iw) / box.width, sy = double(ih) / box.height;
  for (int y = 0; y < window.height(); ++y)
  {
    for (int x = 0; x < window.width(); ++x)
    {
      const bool lit = brightness(window.pixel(x, y)) > 0.5;
      // The window pixel's extent in image-edge coordinates (image pixel u spans [u, u + 1)).
      const double ex0 = (x - box.left) * sx, ex1 = (x + 1 - box.left) * sx;
      const double ey0 = (y - box.top) * sy, ey1 = (y + 1 - box.top) * sy;
      const int u = int(std::floor(ex0)), v = int(std::floor(ey0));
      if (u < 0 || v < 0 || u >= iw || v >= ih)
      {
        outside += lit;  // letterbox bars
        continue;
      }
      if (ex1 > u + 1 + 1e-9 || ey1 > v + 1 + 1e-9)
      {
        continue;  // straddles an edge
      }
      const bool drawn = mask[std::size_t(v) * iw + u] != 0;
      outside += lit && !drawn;
      inside += drawn && !lit;
    }
  }
  return {outside, inside};
}
}  // namespace

class CrosshairsTest : public ProjectorCameraTest
{
protected:
  /// Shows the lens and the crosshairs; returns the grabbed window once it shows `count` crosses.
  QImage showCrosshairs(const sensor_msgs::CameraInfo& info, int rows, int cols)
  {
    info_pub_.publish(info);
    EXPECT_TRUE(waitFor([&] { return projector_->hasLens() && int(projector_->lens().width()) == int(info.width); }));
    EXPECT_TRUE(waitFor([&] { return projector_->outputWindow() && projector_->outputWindow()->isVisible(); }));
    projector_->subProp("Test pattern")->setValue("Crosshairs");
    projector_->subProp("Test pattern")->subProp("Rows")->setValue(rows);
    projector_->subProp("Test pattern")->subProp("Columns")->setValue(cols);
    const PixelOracle oracle(info, m_);
    return grabWhen([&](const QImage& w) { return measure(w, oracle, rows, cols).size() == std::size_t(rows * cols); });
  }

  /// The crosshair centres found in `window`, image pixels, in id order (only those found).
  std::vector<Vec2> measure(const QImage& window, const PixelOracle& oracle, int rows, int cols) const
  {
    const Letterbox box = oracle.box(window.width(), window.height());
    const int reach = int(std::ceil(std::min(box.width, box.height) / 10.0));
    std::vector<Vec2> found;
    for (const Vec2& p : handPattern(oracle.imageWidth(), oracle.imageHeight(), rows, cols))
    {
      Vec2 centre;
      if (crossCentre(window, oracle.toWindow(box, p), reach, centre))
      {
        found.push_back(toImage(box, oracle, centre));
      }
    }
    return found;
  }

  /// Checks the crosses against the hand-computed pixels and that nothing else is lit.
  void expectPattern(const QImage& window, const sensor_msgs::CameraInfo& info, int rows, int cols)
  {
    const PixelOracle oracle(info, m_);
    const std::vector<Vec2> expected = handPattern(oracle.imageWidth(), oracle.imageHeight(), rows, cols);
    const std::vector<Vec2> found = measure(window, oracle, rows, cols);
    ASSERT_EQ(found.size(), expected.size()) << "crosses found near the hand-computed pixels";
    double worst = 0.0;
    for (std::size_t i = 0; i < expected.size(); ++i)
    {
      const double error = std::hypot(found[i].x - expected[i].x, found[i].y - expected[i].y);
      EXPECT_LE(error, kBound) << "crosshair " << i + 1 << ": expected (" << expected[i].x << ", " << expected[i].y
                               << "), rendered (" << found[i].x << ", " << found[i].y << ")";
      worst = std::max(worst, error);
    }
    std::printf("  %dx%d, %d x %d crosshairs: largest centre error %.3f px\n", oracle.imageWidth(),
                oracle.imageHeight(), rows, cols, worst);
    // Exactly the rectangles the core asks for (the core decides the shapes; the display must draw
    // them pixel for pixel, and nothing of the scene or the background).
    const auto rects = rviz_projector::crosshairPatternRects(
        rviz_projector::crosshairPattern(oracle.imageWidth(), oracle.imageHeight(), rows, cols), oracle.imageWidth(),
        oracle.imageHeight());
    const auto wrong = litOutsideAndDarkInside(window, oracle.box(window.width(), window.height()), oracle.imageWidth(),
                                               oracle.imageHeight(), rects);
    EXPECT_EQ(wrong.first, 0) << "window pixels lit outside the pattern's rectangles";
    EXPECT_EQ(wrong.second, 0) << "pattern pixels not lit";
  }

  Mount m_ = bodyMount({0.0, 0.0, 1.2}, 0.0, 0.9, 0.0);
};

TEST_F(CrosshairsTest, ThreeByThreeAtTheRulesPixelsAndNothingElse)
{
  const sensor_msgs::CameraInfo info = projectorInfo(1280, 800, 1300, 639.5, 399.5);
  mount(m_);
  // A floor target in the middle of the projector's view: the scene must not show behind the pattern.
  const PixelOracle oracle(info, m_);
  addTarget(oracle.floorPoint({700, 430}), 0.05);
  projector_->subProp("Background color")->setValue(QColor(90, 0, 0));
  const QImage window = showCrosshairs(info, 3, 3);
  EXPECT_EQ(handPattern(1280, 800, 3, 3)[0].x, 128.0);  // the rule's example (issue 12 / crosshair_pattern.h)
  expectPattern(window, info, 3, 3);
  EXPECT_EQ(countColour(window, kGreen, 60), 0) << "the scene shows behind the crosshairs";
  EXPECT_EQ(countColour(window, qRgb(90, 0, 0), 20), 0) << "the background is black under the crosshairs";
  // Off again: the scene (the target) and the background colour come back.
  projector_->subProp("Test pattern")->setValue("Off");
  const QImage scene = grabWhen([&](const QImage& w) { return countColour(w, kGreen, 60) > 100; });
  EXPECT_GT(countColour(scene, kGreen, 60), 100);
  EXPECT_EQ(countColour(scene, kWhite, 30), 0);
}

TEST_F(CrosshairsTest, FourRowsFiveColumnsOnAHalfSizeImage)
{
  // 640x400 shown x2 in the window (or as the letterbox allows): rows and columns are not swapped.
  const sensor_msgs::CameraInfo info = projectorInfo(640, 400, 650, 319.5, 199.5);
  mount(m_);
  const QImage window = showCrosshairs(info, 4, 5);
  expectPattern(window, info, 4, 5);
  // And a single crosshair in the centre.
  projector_->subProp("Test pattern")->subProp("Rows")->setValue(1);
  projector_->subProp("Test pattern")->subProp("Columns")->setValue(1);
  const PixelOracle oracle(info, m_);
  const QImage one = grabWhen([&](const QImage& w) {
    return measure(w, oracle, 1, 1).size() == 1 && measure(w, oracle, 4, 5).size() < 20;
  });
  expectPattern(one, info, 1, 1);
}

TEST_F(CrosshairsTest, IndependentOfThePoseAndShownWithoutTf)
{
  const sensor_msgs::CameraInfo info = projectorInfo(1280, 800, 1300, 652.0, 380.0);
  mount(m_);
  const QImage first = showCrosshairs(info, 3, 3);
  expectPattern(first, info, 3, 3);
  // Another mount: the same pixels.
  mount(bodyMount({0.4, -0.3, 0.8}, 0.1, 0.5, 0.6));
  EXPECT_TRUE(waitFor([&] {
    projector_->renderNow();
    return statusOf(projector_, "Transform").level == rviz::StatusProperty::Ok;
  }));
  EXPECT_TRUE(grabWhen([&](const QImage& w) { return w == first; }) == first) << "the pattern moved with the mount";
  // No tf for the projector's frame at all: the pose status says so, the pattern stays.
  projector_->subProp("Frame")->setValue("no_such_frame");
  ASSERT_TRUE(waitFor([&] {
    projector_->renderNow();
    return statusOf(projector_, "Transform").level == rviz::StatusProperty::Error;
  }));
  const QImage without_tf = grabWhen([&](const QImage& w) { return w == first; });
  EXPECT_TRUE(without_tf == first) << "the pattern is not shown without tf";
  expectPattern(without_tf, info, 3, 3);
  // Metric grid needs the pose: without tf the projector goes dark.
  projector_->subProp("Test pattern")->setValue("Metric grid");
  EXPECT_EQ(countColour(grabWhen([&](const QImage& w) { return countColour(w, kWhite, 30) == 0; }), kWhite, 30), 0);
}

TEST_F(CrosshairsTest, PublishedImageShowsThePattern)
{
  const sensor_msgs::CameraInfo info = projectorInfo(1280, 800, 1300, 639.5, 399.5);
  mount(m_);
  sensor_msgs::Image::ConstPtr image;
  ros::Subscriber sub = nh_.subscribe<sensor_msgs::Image>(
      "/test/crosshairs/image", 1, [&](const sensor_msgs::Image::ConstPtr& m) { image = m; });
  projector_->subProp("Image output")->subProp("Image topic")->setValue("/test/crosshairs/image");
  projector_->subProp("Image output")->subProp("Image rate")->setValue(20.0);
  projector_->subProp("Image output")->setValue(true);
  const QImage window = showCrosshairs(info, 3, 3);
  expectPattern(window, info, 3, 3);
  // An image published after the pattern is up: the image part of the window, pixel for pixel.
  const PixelOracle oracle(info, m_);
  const Letterbox box = oracle.box(window.width(), window.height());
  const QImage expected = window.copy(box.left, box.top, box.width, box.height);
  ASSERT_TRUE(waitFor([&] {
    projector_->renderNow();
    return image && int(image->width) == expected.width() && int(image->height) == expected.height() &&
           image->encoding == "rgb8" &&
           QImage(image->data.data(), int(image->width), int(image->height), int(image->step), QImage::Format_RGB888) ==
               expected.convertToFormat(QImage::Format_RGB888);
  })) << "no published image equal to the window's image part";
}

TEST_F(CrosshairsTest, NeverInRvizsMainView)
{
  const sensor_msgs::CameraInfo info = projectorInfo(1280, 800, 1300, 639.5, 399.5);
  mount(m_);
  projector_->subProp("Footprint in main view")->setValue(false);
  info_pub_.publish(info);
  ASSERT_TRUE(waitFor([&] { return projector_->hasLens(); }));
  const QImage before = rviz_->renderMainView();
  const QImage window = showCrosshairs(info, 3, 3);
  expectPattern(window, info, 3, 3);
  const QImage during = rviz_->renderMainView();
  EXPECT_EQ(countColour(during, kWhite, 30), countColour(before, kWhite, 30)) << "crosshairs in rviz's main view";
  EXPECT_TRUE(during == before) << "rviz's main view changed with the projector's test pattern";
}

TEST_F(CrosshairsTest, RoundTripFromRenderedPixelsRecoversTheMount)
{
  // The true mount of the projector (what the solver must find). The floor points are where the
  // rendered crosshairs land from it: image_geometry's ray through each RENDERED centre, met with
  // the floor by the test's own transform (PixelOracle::floorPoint).
  const double roll = 0.05, pitch = 0.85, yaw = -0.12;
  const rviz_projector::Vec3 position{0.15, -0.05, 1.1};
  const Mount truth = bodyMount(position, roll, pitch, yaw);
  const sensor_msgs::CameraInfo info = projectorInfo(1280, 800, 1900, 640, 817);  // the PA503W's lens
  // The display is at a WRONG mount while the pattern renders: the pattern is in image space and the
  // solver needs no starting pose, so where the display thinks the projector is does not matter.
  mount(bodyMount({0.5, 0.3, 0.7}, -0.1, 0.4, 0.3));
  const QImage window = showCrosshairs(info, 3, 3);
  const PixelOracle oracle(info, truth);
  const std::vector<Vec2> rendered = measure(window, oracle, 3, 3);
  const std::vector<rviz_projector::Crosshair> pattern = rviz_projector::crosshairPattern(1280, 800, 3, 3);
  ASSERT_EQ(rendered.size(), pattern.size());
  std::vector<rviz_projector::FloorPoint> points;
  for (std::size_t i = 0; i < pattern.size(); ++i)
  {
    rviz_projector::FloorPoint p;
    p.id = pattern[i].id;
    p.pixel = pattern[i].pixel;  // the template's pixel, as the user's points.yaml has it
    const Vec2 floor = oracle.floorPoint(rendered[i]);
    p.world = rviz_projector::Vec3{floor.x, floor.y, 0.0};
    points.push_back(p);
  }
  const rviz_projector::PinholeModel lens(1280, 800, 1900, 1900, 640, 817);
  const rviz_projector::MountSolution solution = rviz_projector::solveMount(lens, points);
  ASSERT_TRUE(solution.ok) << solution.error;
  const auto deg = [](double rad) { return rad * 180.0 / M_PI; };
  std::printf("  recovered x %.5f y %.5f z %.5f roll %.4f pitch %.4f yaw %.4f deg (rms %.3f px)\n", solution.mount.x,
              solution.mount.y, solution.mount.z, deg(solution.mount.roll), deg(solution.mount.pitch),
              deg(solution.mount.yaw), solution.rms_px);
  // The rendered centres are whole pixels exactly where the template says, so this is the issue's
  // exact-points case: 0.1 mm and 0.01 deg (well within the 1 mm / 0.05 deg a calibration needs).
  // A pattern drawn one pixel off (fx = 1900) would still pass 1 mm / 0.05 deg: 0.2 mm, 0.03 deg.
  constexpr double kMetres = 0.0001, kDegrees = 0.01;
  EXPECT_NEAR(solution.mount.x, position.x, kMetres);
  EXPECT_NEAR(solution.mount.y, position.y, kMetres);
  EXPECT_NEAR(solution.mount.z, position.z, kMetres);
  EXPECT_NEAR(deg(solution.mount.roll), deg(roll), kDegrees);
  EXPECT_NEAR(deg(solution.mount.pitch), deg(pitch), kDegrees);
  EXPECT_NEAR(deg(solution.mount.yaw), deg(yaw), kDegrees);
  EXPECT_TRUE(solution.outliers.empty());
}

// --- configs: Test pattern was a bool before issue 12 ---------------------------------------------

class CrosshairsConfigTest : public RvizTest
{
protected:
  rviz::Display* loadProjector(const std::string& test_pattern_yaml)
  {
    const std::string yaml = R"(
Displays:
  - Class: rviz_projector/ProjectorCamera
    Name: Projector
    Enabled: false
    Topic: /test/projector/camera_info
)" + test_pattern_yaml;
    rviz::Config config;
    rviz::YamlConfigReader reader;
    reader.readString(config, QString::fromStdString(yaml));
    EXPECT_FALSE(reader.error()) << reader.errorMessage().toStdString();
    rviz_->manager()->load(config);
    rviz::DisplayGroup* root = rviz_->manager()->getRootDisplayGroup();
    return root->numDisplays() == 1 ? root->getDisplayAt(0) : nullptr;
  }
  static std::string pattern(rviz::Display* d)
  {
    return d->subProp("Test pattern")->getValue().toString().toStdString();
  }
};

TEST_F(CrosshairsConfigTest, OldTrueLoadsAsMetricGridAndFalseAsOff)
{
  rviz::Display* d = loadProjector("    Test pattern: true\n");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(pattern(d), "Metric grid");
  EXPECT_TRUE(d->subProp("Test pattern")->subProp("Rows")->getHidden());
  EXPECT_FALSE(statusOf(d, "Config").present) << statusOf(d, "Config").text.toStdString();
  d = loadProjector("    Test pattern: false\n");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(pattern(d), "Off");
  EXPECT_FALSE(statusOf(d, "Config").present);
}

TEST_F(CrosshairsConfigTest, CrosshairsWithRowsAndColumnsLoadAndNonsenseIsReported)
{
  rviz::Display* d = loadProjector("    Test pattern:\n      Value: Crosshairs\n      Rows: 4\n      Columns: 2\n");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(pattern(d), "Crosshairs");
  EXPECT_EQ(d->subProp("Test pattern")->subProp("Rows")->getValue().toInt(), 4);
  EXPECT_EQ(d->subProp("Test pattern")->subProp("Columns")->getValue().toInt(), 2);
  EXPECT_FALSE(d->subProp("Test pattern")->subProp("Columns")->getHidden());
  EXPECT_FALSE(statusOf(d, "Config").present) << statusOf(d, "Config").text.toStdString();
  d = loadProjector("    Test pattern:\n      Value: Sparkles\n      Rows: 99\n");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(pattern(d), "Off");
  EXPECT_EQ(d->subProp("Test pattern")->subProp("Rows")->getValue().toInt(),
            rviz_projector::CrosshairPatternSize::kMaxRowsCols);
  const Status s = statusOf(d, "Config");
  ASSERT_TRUE(s.present);
  EXPECT_NE(s.text.indexOf("Test pattern: 'Sparkles' -> Off"), -1) << s.text.toStdString();
  EXPECT_NE(s.text.indexOf("Rows: '99'"), -1) << s.text.toStdString();
}
