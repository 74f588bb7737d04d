// ProjectorCamera in rendered pixels against the independent oracle (projector_test_fixture.h:
// image_geometry on the raw CameraInfo, the letterbox rule by hand): floor targets land where
// image_geometry says for centred and off-axis lenses, Tx/Ty, binning and an ROI, for a moving
// projector, and with K when P is all zero; the image area of awkward window/image size pairs is
// exactly the hand-computed rectangle.
//
// Bound: 0.25 px, in window pixels and in image pixels (the larger counts). The core is held to
// 0.05 px against image_geometry in its unit tests; rendered pixels cannot be measured that
// finely (rasterisation of a disc edge, centroid of 8-bit pixels), so these tests use the same
// 0.25 px as the other pixel tests.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include <QColor>
#include <QGuiApplication>
#include <QScreen>
#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Path.h>
#include <rviz/display.h>

#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output_window.h"
#include "projector_test_fixture.h"

using rviz_projector_test::bodyMount;
using rviz_projector_test::distortedInfo;
using rviz_projector_test::greenCentroid;
using rviz_projector_test::kDemoMount;
using rviz_projector_test::PixelOracle;
using rviz_projector_test::ProjectorSceneTest;
using rviz_projector_test::Letterbox;
using rviz_projector_test::Mount;
using rviz_projector_test::projectorInfo;
using rviz_projector_test::saveShot;
using rviz_projector_test::ProjectorCameraTest;
using rviz_projector_test::Vec2;

namespace
{
constexpr double kBound = 0.25;
}  // namespace

TEST_F(ProjectorCameraTest, PixelAccuracyCentredLensLookingDown)
{
  const Mount down{{0.3, -0.2, 2.0}, 1.0, 0.0, 0.0, 0.0};  // optical z = -world z
  const double worst = pixelAccuracy(projectorInfo(1280, 800, 1000, 639.5, 399.5), down,
                                     {{640, 400}, {100.25, 80.5}, {1180, 90}, {1200.7, 730.2}, {70, 700}});
  std::printf("centred lens: max error %.3f px\n", worst);
  EXPECT_LE(worst, kBound);
}

TEST_F(ProjectorCameraTest, PixelAccuracyReferenceProjectorOffAxis)
{
  // ViewSonic PA503W as calibrated in the reference set-up: cy = 817, beyond the bottom edge.
  const Mount m = bodyMount({0.0, 0.0, 1.2}, 0.0, 0.6, 0.0);
  const double worst = pixelAccuracy(projectorInfo(1280, 800, 1900, 640, 817), m,
                                     {{640, 400}, {60, 40}, {1220, 50}, {1230, 760}, {50, 770}});
  std::printf("reference projector: max error %.3f px\n", worst);
  EXPECT_LE(worst, kBound);
}

TEST_F(ProjectorCameraTest, PixelAccuracyRolledAndYawedMount)
{
  const Mount m = bodyMount({1.0, 2.0, 1.5}, 0.15, 0.8, 0.7);
  const double worst = pixelAccuracy(projectorInfo(1024, 768, 900, 530.3, 360.8), m,
                                     {{512, 384}, {50, 50}, {980, 60}, {990, 720}, {40, 730}});
  std::printf("rolled and yawed mount: max error %.3f px\n", worst);
  EXPECT_LE(worst, kBound);
}

TEST_F(ProjectorCameraTest, PixelAccuracyWithTxAndTy)
{
  // The second projector of a stereo pair: P[3] = Tx = -fx * 0.1 m, P[7] = Ty = fy * 0.04 m (K
  // unchanged). 2 m above the floor that moves the picture by -65 px and +26 px.
  sensor_msgs::CameraInfo info = projectorInfo(1280, 800, 1300, 652.4, 388.1);
  info.P[3] = -130.0;
  info.P[7] = 52.0;
  const Mount down{{0.3, -0.2, 2.0}, 1.0, 0.0, 0.0, 0.0};
  const double worst =
      pixelAccuracy(info, down, {{640, 400}, {90.5, 70.25}, {1190, 80}, {1180.3, 720.6}, {80, 710}});
  std::printf("Tx/Ty: max error %.3f px\n", worst);
  EXPECT_LE(worst, kBound);
}

TEST_F(ProjectorCameraTest, PixelAccuracyWithBinning2x2)
{
  // A 1280x800 calibration used at 2x2 binning: a 640x400 image (scaled x2 into a 1280x800 screen).
  sensor_msgs::CameraInfo info = projectorInfo(1280, 800, 1300, 650.3, 380.7);
  info.binning_x = 2;
  info.binning_y = 2;
  const Mount m = bodyMount({0.0, 0.0, 1.2}, 0.0, 0.9, 0.1);
  const double worst = pixelAccuracy(info, m, {{320, 200}, {50, 40}, {590, 45}, {600, 360}, {40, 350}});
  std::printf("binning 2x2: max error %.3f px\n", worst);
  EXPECT_LE(worst, kBound);
}

TEST_F(ProjectorCameraTest, PixelAccuracyWithRegionOfInterest)
{
  // A 640x400 ROI at 400,250 of a 1280x800 calibration (rectified): the ROI's image, letterboxed.
  sensor_msgs::CameraInfo info = projectorInfo(1280, 800, 1300, 650.3, 380.7);
  info.roi.x_offset = 400;
  info.roi.y_offset = 250;
  info.roi.width = 640;
  info.roi.height = 400;
  info.roi.do_rectify = true;
  const Mount m = bodyMount({0.0, 0.0, 1.2}, 0.0, 0.9, -0.1);
  const double worst = pixelAccuracy(info, m, {{320, 200}, {50, 40}, {590, 45}, {600, 360}, {40, 350}});
  std::printf("ROI: max error %.3f px\n", worst);
  EXPECT_LE(worst, kBound);
}

TEST_F(ProjectorCameraTest, PixelAccuracyWithRegionOfInterestAndBinning)
{
  // An 800x500 ROI at 200,100, binned 2x2: a 400x250 image.
  sensor_msgs::CameraInfo info = projectorInfo(1280, 800, 1300, 650.3, 380.7);
  info.roi.x_offset = 200;
  info.roi.y_offset = 100;
  info.roi.width = 800;
  info.roi.height = 500;
  info.roi.do_rectify = true;
  info.binning_x = 2;
  info.binning_y = 2;
  const Mount m = bodyMount({0.0, 0.0, 1.2}, 0.0, 0.8, 0.0);
  const double worst = pixelAccuracy(info, m, {{200, 125}, {40, 30}, {360, 35}, {365, 220}, {30, 215}});
  std::printf("ROI and binning: max error %.3f px\n", worst);
  EXPECT_LE(worst, kBound);
}

TEST_F(ProjectorSceneTest, MovingProjectorKeepsAWorldTargetOnItsProjection)
{
  addTarget({1.2, 0.1}, 0.03);
  ASSERT_TRUE(waitFor([&] { return targetsReady(); }));
  for (double dx : {0.0, 0.07, -0.05})
  {
    Mount moved = kDemoMount;
    moved.position.x += dx;
    mount(moved);
    const Vec2 expected = windowPixel({1.2, 0.1}, moved);
    Vec2 centroid;
    int count = 0;
    // Until the new pose reached the picture (or the timeout): then judged.
    const QImage frame = imagePart(grabWhen([&](const QImage& image) {
      const QImage part = imagePart(image);
      return greenCentroid(part, expected, 40, centroid, count) && std::hypot(centroid.x - expected.x, centroid.y - expected.y) < 1.0;
    }));
    ASSERT_TRUE(greenCentroid(frame, expected, 40, centroid, count)) << "dx " << dx;
    EXPECT_NEAR(centroid.x, expected.x, 1.0) << "dx " << dx;
    EXPECT_NEAR(centroid.y, expected.y, 1.0) << "dx " << dx;
  }
}

TEST_F(ProjectorSceneTest, PAllZeroProjectsWithK)
{
  // K differs from P (and from the lens in use so far) in focal length and principal point: the
  // target lands tens of pixels apart by the two, so the picture tells which one was used.
  const Vec2 target{1.3, 0.15};
  addTarget(target, 0.04);
  ASSERT_TRUE(waitFor([&] { return targetsReady(); }));
  sensor_msgs::CameraInfo both = info_;
  both.K = {1200, 0, 600.5, 0, 1150, 430.5, 0, 0, 1};
  sensor_msgs::CameraInfo k_as_p = both;  // what "P all zero" means (CameraInfo.msg): P = [K | 0]
  k_as_p.P = {1200, 0, 600.5, 0, 0, 1150, 430.5, 0, 0, 0, 1, 0};
  const PixelOracle by_p(both, kDemoMount), by_k(k_as_p, kDemoMount);
  ASSERT_GT(rviz_projector::distance(by_p.imagePixel(target), by_k.imagePixel(target)), 20.0);
  // The target's centroid in the window, and where `oracle` says it must be.
  Vec2 centroid, expected;
  auto at = [&](const PixelOracle& oracle) {
    return [&, o = &oracle](const QImage& window) {
      expected = o->toWindow(o->box(window.width(), window.height()), o->imagePixel(target));
      int count = 0;
      return greenCentroid(window, expected, 60, centroid, count) && rviz_projector::distance(centroid, expected) < 1.0;
    };
  };
  // P given: P, not K.
  info_pub_.publish(both);
  grabWhen(at(by_p));
  EXPECT_LT(rviz_projector::distance(centroid, expected), 1.0)
      << "P in use: target at " << centroid.x << "," << centroid.y << ", expected " << expected.x << "," << expected.y;
  // P all zero: K.
  sensor_msgs::CameraInfo k_only = both;
  k_only.P.fill(0);
  info_pub_.publish(k_only);
  grabWhen(at(by_k));
  EXPECT_TRUE(projector_->hasLens());
  EXPECT_EQ(statusOf(projector_, "CameraInfo").level, rviz::StatusProperty::Ok);
  EXPECT_LT(rviz_projector::distance(centroid, expected), 1.0)
      << "K in use: target at " << centroid.x << "," << centroid.y << ", expected " << expected.x << "," << expected.y;
}

namespace
{
/// An image size shown in a window size.
struct SizePair
{
  int image_width, image_height, window_width, window_height;
};

void PrintTo(const SizePair& p, std::ostream* os)
{
  *os << p.image_width << "x" << p.image_height << " in " << p.window_width << "x" << p.window_height;
}

class LetterboxPixelsTest : public ProjectorCameraTest, public ::testing::WithParamInterface<SizePair>
{
};
}  // namespace

TEST_P(LetterboxPixelsTest, ImageAreaIsExactlyTheComputedRectangle)
{
  const SizePair p = GetParam();
  const Letterbox expected = rviz_projector_test::letterbox(p.window_width, p.window_height, p.image_width,
                                                            p.image_height);
  mount(bodyMount({0.0, 0.0, 1.2}, 0.0, 0.9, 0.0));
  info_pub_.publish(projectorInfo(unsigned(p.image_width), unsigned(p.image_height), p.image_width,
                                  (p.image_width - 1) / 2.0, (p.image_height - 1) / 2.0));
  ASSERT_TRUE(waitFor([&] { return projector_->hasLens(); }));
  projector_->subProp("Full screen")->setValue(false);
  ASSERT_TRUE(waitFor([&] {
    return projector_->outputWindow() && projector_->outputWindow()->isVisible() &&
           !projector_->outputWindow()->isFullScreen();
  }));
  // On the primary screen's top left corner: every size here fits there whole (a window reaching
  // past its screen's edge is grabbed clipped).
  projector_->outputWindow()->setGeometry(
      QRect(QGuiApplication::primaryScreen()->geometry().topLeft(), QSize(p.window_width, p.window_height)));
  ASSERT_TRUE(waitFor([&] {
    return projector_->outputWindow()->size() == QSize(p.window_width, p.window_height);
  })) << "window is " << projector_->outputWindow()->width() << "x" << projector_->outputWindow()->height();
  // Only now white: the image area is white, the letterbox bars stay black.
  projector_->subProp("Background color")->setValue(QColor(255, 255, 255));
  auto boundsOf = [](const QImage& image) { return rviz_projector_test::litBounds(image); };
  auto same = [](const Letterbox& a, const Letterbox& b) {
    return a.left == b.left && a.top == b.top && a.width == b.width && a.height == b.height;
  };
  const QImage frame = grabWhen([&](const QImage& image) {
    return image.size() == QSize(p.window_width, p.window_height) && same(boundsOf(image), expected);
  }, 3.0);
  ASSERT_EQ(frame.size(), QSize(p.window_width, p.window_height));
  const Letterbox lit = boundsOf(frame);
  // First and last lit columns and rows.
  EXPECT_EQ(lit.left, expected.left);
  EXPECT_EQ(lit.left + lit.width - 1, expected.left + expected.width - 1);
  EXPECT_EQ(lit.top, expected.top);
  EXPECT_EQ(lit.top + lit.height - 1, expected.top + expected.height - 1);
  // All of it lit: a full white rectangle.
  EXPECT_EQ(rviz_projector_test::countColour(frame, qRgb(255, 255, 255), 8), expected.width * expected.height);
  std::printf("  %dx%d in %dx%d: expected %dx%d at %d,%d, lit %dx%d at %d,%d\n", p.image_width, p.image_height,
              p.window_width, p.window_height, expected.width, expected.height, expected.left, expected.top,
              lit.width, lit.height, lit.left, lit.top);
}

// Chosen where rounding is awkward: 1024x768 in 854x480 and in 637x574 are among the ~9% of pairs
// that OGRE's truncated relative viewport puts one pixel off; 640x480 in 853x480 fits 1:1 in
// height (odd bars); 1280x800 in 1281x801 scales up by a hair; 800x600 in 799x599 scales down by
// one; 1280x800 in 1000x700 letterboxes top and bottom.
INSTANTIATE_TEST_SUITE_P(AwkwardPairs, LetterboxPixelsTest,
                         ::testing::Values(SizePair{1024, 768, 854, 480}, SizePair{1024, 768, 637, 574},
                                           SizePair{640, 480, 853, 480}, SizePair{1280, 800, 1281, 801},
                                           SizePair{800, 600, 799, 599}, SizePair{1280, 800, 1000, 700}));

// Issue 24: through a distorting lens, the targets land where cv::projectPoints with K and D puts
// them (the oracle: projector_test_fixture.cpp), for the three lenses on its 1280x800,
// f = 1900 projector, targets out to the image corners, where ignoring D misplaces them by 16-69 px.
namespace
{
const std::vector<Vec2> kCornerTargets{{640, 400}, {60, 45}, {1220, 50}, {1225, 755}, {55, 760}, {330, 200}};
}  // namespace

TEST_F(ProjectorCameraTest, PixelAccuracyThroughABarrelLens)
{
  const Mount down{{0.3, -0.2, 2.0}, 1.0, 0.0, 0.0, 0.0};
  const double worst = pixelAccuracy(distortedInfo({-0.05, 0, 0, 0, 0}), down, kCornerTargets);
  std::printf("k1 = -0.05: max error %.3f px\n", worst);
  EXPECT_LE(worst, kBound);
}

TEST_F(ProjectorCameraTest, PixelAccuracyThroughAPincushionLens)
{
  const Mount down{{0.3, -0.2, 2.0}, 1.0, 0.0, 0.0, 0.0};
  const double worst = pixelAccuracy(distortedInfo({0.10, 0, 0, 0, 0}), down, kCornerTargets);
  std::printf("k1 = +0.10: max error %.3f px\n", worst);
  EXPECT_LE(worst, kBound);
}

TEST_F(ProjectorCameraTest, PixelAccuracyThroughAWideAngleLensOnAPitchedMount)
{
  const Mount m = bodyMount({0.0, 0.0, 1.2}, 0.0, 0.6, 0.0);
  const double worst = pixelAccuracy(distortedInfo({-0.2, 0.05, 0, 0, 0}), m, kCornerTargets);
  std::printf("k1 = -0.2, k2 = 0.05: max error %.3f px\n", worst);
  EXPECT_LE(worst, kBound);
}

TEST_F(ProjectorCameraTest, PixelAccuracyThroughAWideAngleLensWithBinningAndRegionOfInterest)
{
  sensor_msgs::CameraInfo info = distortedInfo({-0.2, 0.05, 0.001, -0.001, 0});
  info.roi.x_offset = 160;
  info.roi.y_offset = 100;
  info.roi.width = 960;
  info.roi.height = 600;
  info.binning_x = 2;
  info.binning_y = 2;
  const Mount down{{0.3, -0.2, 2.0}, 1.0, 0.0, 0.0, 0.0};
  const double worst = pixelAccuracy(info, down, {{240, 150}, {30, 25}, {450, 30}, {455, 275}, {25, 280}});
  std::printf("wide lens, ROI 960x600+160+100, binning 2x2: max error %.3f px\n", worst);
  EXPECT_LE(worst, kBound);
}
