// ProjectorCamera: unusable and odd CameraInfos, frames and stamps. Part of the bad-input matrix of issue 4 in a real rviz (robustness_fixtures.h);
// run by test/rviz/robustness_camera.test.
#include "robustness_fixtures.h"

TEST_F(CameraRobustness, UnusableCameraInfosAreErrorsAndShowBackgroundOnly)
{
  struct Case
  {
    const char* what;
    std::function<void(sensor_msgs::CameraInfo&)> spoil;
    std::string error;  // the part of "Unusable CameraInfo: <error>; the projector shows background only"
  };
  const Case cases[] = {
      {"width 0", [](sensor_msgs::CameraInfo& i) { i.width = 0; }, "image size is 0x800 (width and height must be > 0)"},
      {"height 0", [](sensor_msgs::CameraInfo& i) { i.height = 0; }, "image size is 1280x0 (width and height must be > 0)"},
      {"20000x20000",
       [](sensor_msgs::CameraInfo& i) {
         i.width = 20000;
         i.height = 20000;
       },
       "image size 20000x20000 exceeds the 16384x16384 limit"},
      {"K and P all zero",
       [](sensor_msgs::CameraInfo& i) {
         i.K.fill(0);
         i.P.fill(0);
       },
       "P and K are all zero (uncalibrated)"},
      {"NaN in P", [](sensor_msgs::CameraInfo& i) { i.P[2] = kNan; }, "P[2] is not finite"},
      {"Inf in P (unused entry)", [](sensor_msgs::CameraInfo& i) { i.P[9] = kInf; }, "P[9] is not finite"},
      {"NaN in K with P zero",
       [](sensor_msgs::CameraInfo& i) {
         i.P.fill(0);
         i.K[4] = kNan;
       },
       "K[4] is not finite"},
      {"Inf in D", [](sensor_msgs::CameraInfo& i) { i.D[1] = -kInf; }, "D[1] is not finite"},
      {"zero focal length", [](sensor_msgs::CameraInfo& i) { i.P[0] = 0; },
       "focal length in P is not positive (fx = 0, fy = 1300)"},
      {"negative focal length", [](sensor_msgs::CameraInfo& i) { i.P[5] = -1300; },
       "focal length in P is not positive (fx = 1300, fy = -1300)"},
      {"negative focal length in K with P zero",
       [](sensor_msgs::CameraInfo& i) {
         i.P.fill(0);
         i.K[0] = -5;
       },
       "focal length in K is not positive (fx = -5, fy = 1300)"},
      {"ROI outside the image",
       [](sensor_msgs::CameraInfo& i) {
         i.roi.x_offset = 1000;
         i.roi.width = 640;
         i.roi.height = 400;
       },
       "region of interest 640x400+1000+0 lies outside the 1280x800 image"},
      {"binning beyond the image", [](sensor_msgs::CameraInfo& i) { i.binning_x = 2000; }, "binning 2000x1 leaves no pixels"},
      // Issue 24: g(r) = r (1 - 7.8 r^6) turns back at r = 54.6^(-1/6) = 0.513 (g = 0.440), inside
      // this lens's corner radius hypot(640, 400) / 1300 = 0.581 (by hand).
      {"D that folds back inside the image",
       [](sensor_msgs::CameraInfo& i) {
         i.distortion_model = "plumb_bob";
         i.D = {0, 0, 0, 0, -7.8};
       },
       "distortion D folds back at the normalised radius r = 0.513 (where it reaches 0.440), inside the image "
       "(its corner is at 0.581): pixels beyond would show two rays or none; refused, nothing is drawn"},
  };
  for (const Case& c : cases)
  {
    sensor_msgs::CameraInfo bad = good_;
    c.spoil(bad);
    const Status s = publishInfo(bad);
    EXPECT_FALSE(projector_->hasLens()) << c.what;
    EXPECT_EQ(s.level, rviz::StatusProperty::Error) << c.what;
    EXPECT_EQ(text(s), "Unusable CameraInfo: " + c.error + "; the projector shows background only") << c.what;
    expectBackgroundOnly(c.what);
    // 20000x20000 is refused before any window or texture is sized for it.
    ASSERT_NE(projector_->outputWindow(), nullptr);
    EXPECT_LE(projector_->outputWindow()->width(), 4096) << c.what;
  }
  ASSERT_TRUE(showGood()) << "a good CameraInfo brings the projection back";
}

TEST_F(CameraRobustness, UsableOddCameraInfos)
{
  struct Case
  {
    const char* what;
    std::function<void(sensor_msgs::CameraInfo&)> change;
    std::string status;
  };
  const Case cases[] = {
      // K unlike the good P before it: a display that kept the old lens, or fell back wrongly, shows.
      // (Pixels: ProjectorSceneTest.PAllZeroProjectsWithK in projector_pixels_test.cpp.)
      {"P all zero falls back to K",
       [](sensor_msgs::CameraInfo& i) {
         i.K = {1200, 0, 600.5, 0, 1150, 430.5, 0, 0, 1};
         i.P.fill(0);
       },
       "1280x800, fx 1200, fy 1150, cx 600.5, cy 430.5"},
      {"1x1",
       [](sensor_msgs::CameraInfo& i) {
         i.width = i.height = 1;
         i.K = {1, 0, 0, 0, 1, 0, 0, 0, 1};
         i.P = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
       },
       "1x1, fx 1, fy 1, cx 0, cy 0"},
      {"binning 2x2",
       [](sensor_msgs::CameraInfo& i) {
         i.binning_x = 2;
         i.binning_y = 2;
       },
       "640x400, fx 650, fy 650, cx 319.75, cy 199.75"},  // (639.5 / 2, as image_geometry bins)
      {"ROI 640x400 at 320,200",
       [](sensor_msgs::CameraInfo& i) {
         i.roi.x_offset = 320;
         i.roi.y_offset = 200;
         i.roi.width = 640;
         i.roi.height = 400;
       },
       "640x400, fx 1300, fy 1300, cx 319.5, cy 199.5"},
      {"NaN in R (not used)", [](sensor_msgs::CameraInfo& i) { i.R[0] = kNan; },
       "1280x800, fx 1300, fy 1300, cx 639.5, cy 399.5"},
      {"16384x16384, the largest accepted",
       [](sensor_msgs::CameraInfo& i) {
         i.width = i.height = 16384;
         i.P[2] = i.K[2] = 8191.5;
         i.P[6] = i.K[5] = 8191.5;
       },
       "16384x16384, fx 1300, fy 1300, cx 8191.5, cy 8191.5"},
  };
  for (const Case& c : cases)
  {
    sensor_msgs::CameraInfo info = good_;
    c.change(info);
    info_pub_.publish(info);
    ASSERT_TRUE(waitFor([&] { return text(statusOf(projector_, "CameraInfo")) == c.status; }))
        << c.what << ": " << text(statusOf(projector_, "CameraInfo"));
    EXPECT_TRUE(projector_->hasLens()) << c.what;
    EXPECT_EQ(statusOf(projector_, "CameraInfo").level, rviz::StatusProperty::Ok) << c.what;
    EXPECT_FALSE(grabProjector(projector_).isNull()) << c.what;
    EXPECT_FALSE(rviz_->renderMainView().isNull()) << c.what;
    // The window is sized to the screen, never to the image (no giant allocation).
    EXPECT_LE(projector_->outputWindow()->width(), 4096) << c.what;
  }
}

TEST_F(CameraRobustness, ProjectorABillionMetresFromTheOriginWithTheTestPattern)
{
  // tf puts the projector 1e9 m away (a broken localisation): the footprint and the test pattern
  // grid (FloorGrid around the projector) are computed there without trouble.
  projector_->subProp("Test pattern")->setValue("Metric grid");
  static_tf_->sendTransform(rviz_projector_test::projectorMount("map", kOptical, 1e9, -1e9, 1.2, 0.9));
  ASSERT_TRUE(waitFor([&] {
    projector_->renderNow();
    return statusOf(projector_, "Footprint").text.startsWith("Lit floor area");
  })) << text(statusOf(projector_, "Footprint"));
  EXPECT_EQ(statusOf(projector_, "Footprint").level, rviz::StatusProperty::Ok);
  EXPECT_EQ(text(statusOf(projector_, "Transform")), "OK");
  EXPECT_FALSE(grabProjector(projector_).isNull());
  EXPECT_FALSE(rviz_->renderMainView().isNull());
}

// 1e20 m away the test pattern's FloorGrid once converted coordinate / cell to a long out of range
// (undefined behaviour, found by the fuzz target under clang's UBSan; fixed: a grid beyond 1e15
// cells draws no lines, test/core/core_regression_test.cpp). What must hold: no crash, a Footprint
// status, rviz renders.
TEST_F(CameraRobustness, ProjectorFarBeyondLongRangeWithTheTestPattern)
{
  projector_->subProp("Test pattern")->setValue("Metric grid");
  static_tf_->sendTransform(rviz_projector_test::projectorMount("map", kOptical, 1e20, 0.0, 1.2, 0.9));
  ASSERT_TRUE(waitFor([&] {
    projector_->renderNow();
    return statusOf(projector_, "Footprint").present;
  }));
  EXPECT_FALSE(rviz_->renderMainView().isNull());
}

TEST_F(CameraRobustness, UnknownDistortionModelIsAWarning)
{
  sensor_msgs::CameraInfo info = good_;
  info.distortion_model = "fisheye";
  info_pub_.publish(info);
  ASSERT_TRUE(waitFor([&] { return statusOf(projector_, "Distortion").present; }));
  EXPECT_EQ(statusOf(projector_, "Distortion").level, rviz::StatusProperty::Warn);
  EXPECT_EQ(text(statusOf(projector_, "Distortion")), "unknown distortion_model 'fisheye' (ignored)");
  EXPECT_EQ(statusOf(projector_, "CameraInfo").level, rviz::StatusProperty::Ok);
  expectProjects("fisheye");
  info.D = {0.1, 0, 0, 0};
  info_pub_.publish(info);
  ASSERT_TRUE(waitFor([&] { return statusOf(projector_, "Distortion").text.startsWith("distortion D"); }));
  EXPECT_EQ(text(statusOf(projector_, "Distortion")),
            "distortion D is not applied (the view uses the ideal pinhole of P); unknown distortion_model 'fisheye' (ignored)");
  info_pub_.publish(good_);
  ASSERT_TRUE(waitFor([&] { return !statusOf(projector_, "Distortion").present; }));
}

TEST_F(CameraRobustness, EmptyAndUnknownFrames)
{
  sensor_msgs::CameraInfo info = good_;
  info.header.frame_id = "";
  info_pub_.publish(info);
  ASSERT_TRUE(waitFor([&] {
    projector_->renderNow();
    return statusOf(projector_, "Transform").level == rviz::StatusProperty::Error;
  }));
  EXPECT_EQ(text(statusOf(projector_, "Transform")),
            "No projector frame: the CameraInfo header has no frame_id and the Frame property is empty");
  expectBackgroundOnly("empty frame");

  info.header.frame_id = "no_such_frame";
  info_pub_.publish(info);
  ASSERT_TRUE(waitFor([&] {
    projector_->renderNow();
    return statusOf(projector_, "Transform").text.startsWith("No transform from projector frame [no_such_frame]");
  })) << text(statusOf(projector_, "Transform"));
  EXPECT_EQ(statusOf(projector_, "Transform").level, rviz::StatusProperty::Error);
  EXPECT_NE(statusOf(projector_, "Transform").text.indexOf("to fixed frame [map]"), -1);
  expectBackgroundOnly("unknown frame");

  // The frame appears later: the projection comes back by itself.
  static_tf_->sendTransform(rviz_projector_test::projectorMount("map", "no_such_frame", 0.0, 0.0, 1.2, 0.9));
  expectProjects("frame appeared");
  EXPECT_EQ(text(statusOf(projector_, "Transform")), "OK");
}

TEST_F(CameraRobustness, StampsFarInThePastOrFutureStillProject)
{
  unsigned width = 1276;  // a different size each time, so that arrival is visible
  for (const ros::Time& stamp : {ros::Time(1, 0), ros::Time::now() + ros::Duration(1e6), ros::Time(4000000000u, 0)})
  {
    sensor_msgs::CameraInfo info = good_;
    info.header.stamp = stamp;
    info.width = ++width;
    info_pub_.publish(info);
    ASSERT_TRUE(waitFor([&] { return projector_->hasLens() && projector_->lens().width() == info.width; }));
    expectProjects("stamp " + std::to_string(stamp.toSec()));
    EXPECT_EQ(text(statusOf(projector_, "Transform")), "OK");
  }
}
