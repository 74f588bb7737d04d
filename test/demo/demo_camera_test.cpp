// demo_camera (issue 24 part 3): the simulated robot camera against an oracle written here.
//
// demo_camera.test starts the node with known parameters; this test reads them back from the
// parameter server and publishes the projector's images itself. The oracle is the forward chain,
// by hand and OpenCV, sharing no code with the node (which goes the other way: camera pixel ->
// undistort -> floor -> projector): projector pixel -> pinhole ray (the test's projector has D = 0)
// -> rotated by tf2's setRPY * the body -> optical quaternion of projector.launch -> the floor z = 0
// -> cv::projectPoints with the camera's pose (tf2 again), K and D. Checks:
//   - before any projector image the floor is ambient (mean 0.25 x 255, noise sigma 2 levels);
//   - CameraInfo carries the K and D set; the static tf base_link -> optical frame is the mount;
//   - a 21 x 21 px bright square shows up where the oracle puts its centre: intensity centroid
//     (background: the window's border; mean of 4 frames) within 0.2 px, at the centre and near
//     the four corners (where the camera's distortion moves it by ~3 px);
//   - the lit patch's edges (50 % level) are where the oracle maps the projector image's border,
//     within 0.2 px;
//   - levels: ambient + gain x luminance for grey mono8, rgb8 red, bgr8 blue, rgba8 green
//     (Rec. 601 weights, alpha ignored); white is 255 (+- noise) inside the lit patch while the floor
//     outside it stays ambient;
//   - exposure delay: after the projector switches at t (ROS time taken just before publishing),
//     every frame stamped before t + delay still shows the old image, and the first frame showing
//     the new one is stamped at t + delay or later (and, as slack for delivery, within 0.25 s of it);
//   - malformed projector images (32FC1, size 0, data size and step mismatches) are refused with a
//     WARN on /rosout naming the problem; frames keep coming, showing the last good image;
//   - parameters that make no sense stop the node with exit status 1 and a FATAL naming them.
// No fixed sleeps: every wait polls a condition until a deadline.

#include "demo_camera_fixture.h"

#include <gtest/gtest.h>
#include <ros/ros.h>

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "../support/child_process.h"

namespace
{
using namespace demo_camera_test;

Harness* harness = nullptr;

TEST(DemoCamera, FloorIsAmbientBeforeAnyProjectorImage)
{
  const Oracle oracle;
  Frame first;
  ASSERT_TRUE(harness->waitForFrame(ros::Time(0), [](const Frame&) { return true; }, first));
  Frame third;
  ASSERT_TRUE(harness->waitForFrame(first.stamp, [&](const Frame& f) { return f.stamp > first.stamp; }, third));
  for (const Frame& frame : harness->framesAfter(ros::Time(0)))
  {
    ASSERT_EQ(frame.image.cols, 640);
    ASSERT_EQ(frame.image.rows, 480);
    cv::Scalar mean, stddev;
    cv::meanStdDev(frame.image, mean, stddev);
    EXPECT_NEAR(mean[0], oracle.ambient, 0.3);
    EXPECT_NEAR(stddev[0], oracle.noise, 0.2);
  }
  EXPECT_EQ(harness->badFrames(), 0);
}

TEST(DemoCamera, CameraInfoAndStaticTfAreTheParameters)
{
  sensor_msgs::CameraInfo info;
  ASSERT_TRUE(Harness::waitFor([&] { return harness->latestInfo(info); }, 15.0));
  EXPECT_EQ(info.header.frame_id, "demo_camera_optical");
  EXPECT_EQ(info.width, 640u);
  EXPECT_EQ(info.height, 480u);
  EXPECT_EQ(info.distortion_model, "plumb_bob");
  const std::array<double, 9> k{param("fx"), 0.0, param("cx"), 0.0, param("fy"), param("cy"), 0.0, 0.0, 1.0};
  for (std::size_t i = 0; i < 9; ++i)
  {
    EXPECT_EQ(info.K[i], k[i]) << "K[" << i << "]";
  }
  EXPECT_EQ(info.D, listParam("D"));
  EXPECT_EQ(info.P[0], k[0]);
  EXPECT_EQ(info.P[2], k[2]);
  EXPECT_EQ(info.P[5], k[4]);
  EXPECT_EQ(info.P[6], k[5]);

  geometry_msgs::TransformStamped tf;
  ASSERT_NO_THROW(tf = harness->buffer().lookupTransform("base_link", "demo_camera_optical", ros::Time(0),
                                                        ros::Duration(15.0)));
  const Mount camera = mountParams("");
  EXPECT_NEAR(tf.transform.translation.x, camera.x, 1e-9);
  EXPECT_NEAR(tf.transform.translation.y, camera.y, 1e-9);
  EXPECT_NEAR(tf.transform.translation.z, camera.z, 1e-9);
  const tf2::Quaternion expected = opticalQuaternion(camera);
  const tf2::Quaternion got(tf.transform.rotation.x, tf.transform.rotation.y, tf.transform.rotation.z,
                            tf.transform.rotation.w);
  EXPECT_NEAR(std::abs(expected.dot(got)), 1.0, 1e-9);
  // The body frame sits in between, as with projector.launch.
  EXPECT_NO_THROW(harness->buffer().lookupTransform("base_link", "demo_camera_link", ros::Time(0), ros::Duration(5.0)));
}

// The calibration's goal is 1 mm on the floor, 0.23 camera pixels at the lit patch's far edge: the
// simulation must be right to a fraction of that. Measured: 0.02 to 0.09 px (mean of 4 frames; a
// single frame's noise alone moves the centroid by up to ~0.1 px); a camera sampled 1/3 px off
// moves it by 0.3 to 0.4 px.
constexpr double kCentroidTolerance = 0.2;
constexpr std::size_t kAveraged = 4;

TEST(DemoCamera, BrightSquareLandsWhereTheOracleSays)
{
  const Oracle oracle;
  // The centre, then near the corners (camera distortion: pixels), none overlapping the previous.
  const std::vector<cv::Point> centres{{640, 400}, {150, 100}, {1130, 700}, {1130, 100}, {150, 700}, {900, 250}};
  cv::Rect previous;
  for (const cv::Point& centre : centres)
  {
    const cv::Rect window = oracle.windowAround(centre, 14);
    ASSERT_TRUE((window & cv::Rect(0, 0, 640, 480)) == window) << "projector pixel " << centre << " out of view";
    const ros::Time sent = harness->publish(blobImage(centre.x, centre.y));
    Frame frame;
    const bool shown = harness->waitForFrame(
        sent,
        [&](const Frame& f) {
          return peak(f, window) > oracle.ambient + 100 &&
                 (previous.area() == 0 || peak(f, previous) < oracle.ambient + 20);
        },
        frame);
    ASSERT_TRUE(shown) << "the square at projector pixel " << centre << " never showed";
    // The mean centroid of this and the next kAveraged - 1 frames (each frame's noise differs).
    const std::vector<Frame> frames = harness->framesFrom(frame, kAveraged);
    ASSERT_EQ(frames.size(), kAveraged);
    cv::Point2d got(0.0, 0.0);
    for (const Frame& f : frames)
    {
      ASSERT_GT(peak(f, window), oracle.ambient + 100) << "the square went away";
      got += centroid(f, window) / static_cast<double>(frames.size());
    }
    const cv::Point2d expected = oracle.cameraPixel(centre);
    EXPECT_LT(cv::norm(got - expected), kCentroidTolerance)
        << "projector pixel " << centre << ": camera centroid " << got << ", oracle " << expected;
    ROS_INFO("square at projector %d,%d: camera centroid (%.3f, %.3f), oracle (%.3f, %.3f), error %.3f px", centre.x,
             centre.y, got.x, got.y, expected.x, expected.y, cv::norm(got - expected));
    previous = window;
  }
}

TEST(DemoCamera, LevelsAreAmbientPlusProjectorLuminance)
{
  const Oracle oracle;
  const double ambient = oracle.ambient;
  struct Case
  {
    std::string encoding;
    std::vector<std::uint8_t> pixel;
    double luminance;  // grey levels, Rec. 601 (cvtColor rounds it)
  };
  const std::vector<Case> cases{
      {"mono8", {100}, 100.0},
      {"rgb8", {255, 0, 0}, std::round(0.299 * 255)},
      {"bgr8", {255, 0, 0}, std::round(0.114 * 255)},
      {"rgba8", {0, 255, 0, 0}, std::round(0.587 * 255)},
      {"bgra8", {0, 0, 0, 255}, 0.0},
      {"mono8", {255}, 255.0},
  };
  const cv::Rect outside(2, 2, 30, 30);  // the camera's top-left corner: beyond the lit patch
  for (const cv::Point2d& top : {cv::Point2d(-0.5, -0.5), cv::Point2d(639.5, -0.5), cv::Point2d(1279.5, -0.5)})
  {
    ASSERT_GT(oracle.cameraPixel(top).y, 50.0) << "the lit patch reaches the corner region";
  }
  for (const Case& c : cases)
  {
    const double expected = std::min(255.0, ambient + oracle.gain * c.luminance);
    const ros::Time sent = harness->publish(projectorImage(c.encoding, c.pixel));
    Frame frame;
    ASSERT_TRUE(harness->waitForFrame(
        sent, [&](const Frame& f) { return interiorNear(oracle, f, expected, 1.5); }, frame))
        << c.encoding << ": never showed " << expected;
    const cv::Rect interior = oracle.windowAround(cv::Point2d(640, 400), 20);
    if (expected < 250.0)
    {
      EXPECT_NEAR(meanOf(frame, interior), expected, 0.6) << c.encoding;
    }
    else
    {
      // White saturates: the noise's upper half is clipped (mean 255 - sigma / sqrt(2 pi)).
      EXPECT_GT(meanOf(frame, interior), 253.5) << c.encoding;
    }
    EXPECT_NEAR(meanOf(frame, outside), ambient, 1.0) << c.encoding << ": the floor outside the lit patch";
  }
}

// The lit patch ends where the projector's image ends: its 50 % level (the projector's last pixel
// blends with the black beyond it at the image border, u = -0.5 or 1279.5, v = -0.5 or 799.5)
// crosses each camera row or column where the oracle maps the border. Mean of 4 frames, within
// 0.2 px (measured 0.01 to 0.06 px).
TEST(DemoCamera, LitPatchEndsWhereTheProjectorImageEnds)
{
  const Oracle oracle;
  const double level = oracle.ambient + 0.5 * oracle.gain * 255.0;
  const ros::Time sent = harness->publish(projectorImage("mono8", {255}));
  Frame white;
  ASSERT_TRUE(harness->waitForFrame(sent, [&](const Frame& f) { return interiorNear(oracle, f, 255.0, 6.0); }, white));
  const std::vector<Frame> frames = harness->framesFrom(white, kAveraged);
  ASSERT_EQ(frames.size(), kAveraged);
  struct Edge
  {
    const char* name;
    cv::Point2d border;   // a projector point on the image border
    cv::Point2d along;    // the border's direction (projector pixels)
    cv::Point2d inward;   // towards the image's inside
  };
  const double right = kProjectorWidth - 0.5, bottom = kProjectorHeight - 0.5;
  std::vector<Edge> edges;
  for (double u : {400.0, 640.0, 880.0})
  {
    edges.push_back({"top (far)", {u, -0.5}, {1, 0}, {0, 1}});
    edges.push_back({"bottom (near)", {u, bottom}, {1, 0}, {0, -1}});
  }
  for (double v : {250.0, 400.0, 550.0})
  {
    edges.push_back({"left", {-0.5, v}, {0, 1}, {1, 0}});
    edges.push_back({"right", {right, v}, {0, 1}, {-1, 0}});
  }
  for (const Edge& edge : edges)
  {
    const cv::Point2d e = oracle.cameraPixel(edge.border);
    const cv::Point2d e1 = oracle.cameraPixel(edge.border - 20.0 * edge.along);
    const cv::Point2d e2 = oracle.cameraPixel(edge.border + 20.0 * edge.along);
    const cv::Point2d in = oracle.cameraPixel(edge.border + 40.0 * edge.inward);
    // Top and bottom edges run across the camera image: scan a column; left and right: a row.
    const bool along_column = std::abs(e2.x - e1.x) > std::abs(e2.y - e1.y);
    double expected, got = 0.0;
    int line, inside, outside;
    if (along_column)
    {
      line = static_cast<int>(std::lround(e.x));
      expected = e1.y + (line - e1.x) * (e2.y - e1.y) / (e2.x - e1.x);
      inside = static_cast<int>(std::lround(in.y));
      outside = static_cast<int>(std::lround(expected)) + (in.y < expected ? 8 : -8);
    }
    else
    {
      line = static_cast<int>(std::lround(e.y));
      expected = e1.x + (line - e1.y) * (e2.x - e1.x) / (e2.y - e1.y);
      inside = static_cast<int>(std::lround(in.x));
      outside = static_cast<int>(std::lround(expected)) + (in.x < expected ? 8 : -8);
    }
    for (const Frame& f : frames)
    {
      got += crossing(f, along_column, line, inside, outside, level) / static_cast<double>(frames.size());
    }
    EXPECT_LT(std::abs(got - expected), 0.2) << edge.name << " edge at projector " << edge.border << ": camera "
                                              << (along_column ? "row " : "column ") << got << ", oracle " << expected;
    ROS_INFO("%s edge at projector (%.1f, %.1f): camera %s %.3f, oracle %.3f, error %.3f px", edge.name,
             edge.border.x, edge.border.y, along_column ? "row" : "column", got, expected, std::abs(got - expected));
  }
}

TEST(DemoCamera, FramesShowTheImageThatArrivedExposureDelayBefore)
{
  const Oracle oracle;
  ASSERT_GT(oracle.delay, 0.2);
  const ros::Time black_sent = harness->publish(projectorImage("mono8", {0}));
  Frame black;
  ASSERT_TRUE(harness->waitForFrame(
      black_sent, [&](const Frame& f) { return interiorNear(oracle, f, oracle.ambient, 3.0); }, black));

  const ros::Time switched = harness->publish(projectorImage("mono8", {255}));
  Frame white;
  ASSERT_TRUE(harness->waitForFrame(switched, [&](const Frame& f) { return interiorNear(oracle, f, 255.0, 6.0); },
                                    white));
  const ros::Time due = switched + ros::Duration(oracle.delay);
  EXPECT_GE(white.stamp, due) << "a frame " << (due - white.stamp).toSec()
                              << " s before the delay showed the new image";
  // Slack for the image's delivery and the frame period (30 Hz): not a measurement of the node.
  EXPECT_LT((white.stamp - due).toSec(), 0.25);
  int old_frames = 0;
  for (const Frame& frame : harness->framesAfter(switched))
  {
    if (frame.stamp < due)
    {
      ++old_frames;
      EXPECT_TRUE(interiorNear(oracle, frame, oracle.ambient, 3.0))
          << "frame stamped " << (frame.stamp - switched).toSec() << " s after the switch";
    }
  }
  EXPECT_GE(old_frames, 3) << "frames stamped within the delay after the switch";
  // And the new image stays.
  Frame later;
  ASSERT_TRUE(harness->waitForFrame(white.stamp + ros::Duration(0.2), [](const Frame&) { return true; }, later));
  for (const Frame& frame : harness->framesAfter(white.stamp))
  {
    EXPECT_TRUE(interiorNear(oracle, frame, 255.0, 6.0));
  }
}

TEST(DemoCamera, MalformedProjectorImagesAreRefusedAndFramesGoOn)
{
  const Oracle oracle;
  const ros::Time good_sent = harness->publish(projectorImage("mono8", {255}));
  Frame good;
  ASSERT_TRUE(harness->waitForFrame(good_sent, [&](const Frame& f) { return interiorNear(oracle, f, 255.0, 6.0); },
                                    good));

  sensor_msgs::Image float_image = projectorImage("mono8", {0});
  float_image.encoding = "32FC1";
  float_image.width = 4;
  float_image.height = 4;
  float_image.step = 16;
  float_image.data.assign(64, 0);
  sensor_msgs::Image empty = projectorImage("mono8", {0});
  empty.width = 0;
  empty.height = 0;
  empty.step = 0;
  empty.data.clear();
  sensor_msgs::Image short_data = projectorImage("mono8", {0});
  short_data.data.resize(1000);
  sensor_msgs::Image short_step = projectorImage("rgb8", {0, 0, 0});
  short_step.step = kProjectorWidth;  // less than width x 3
  short_step.data.resize(static_cast<std::size_t>(kProjectorWidth) * kProjectorHeight);
  const ros::Time bad_sent = harness->publish(float_image);
  harness->publish(empty);
  harness->publish(short_data);
  harness->publish(short_step);

  for (const std::string& reason : {std::string("'32FC1'"), std::string("0x0"), std::string("data size 1000"),
                                    std::string("step 1280 (at least 3840)")})
  {
    EXPECT_TRUE(Harness::waitFor([&] { return harness->warned(reason); }, 15.0)) << "no WARN naming " << reason;
  }
  // Frames keep coming well past the delay, still showing the last good image.
  Frame late;
  ASSERT_TRUE(harness->waitForFrame(bad_sent + ros::Duration(oracle.delay + 0.5), [](const Frame&) { return true; },
                                    late));
  const std::vector<Frame> after = harness->framesAfter(bad_sent);
  EXPECT_GE(after.size(), 10u);
  for (const Frame& frame : after)
  {
    EXPECT_TRUE(interiorNear(oracle, frame, 255.0, 6.0));
  }
  EXPECT_EQ(harness->badFrames(), 0);
}

/// Runs the node binary as `name` (its parameters set beforehand; no shell), at most 20 s; its exit
/// status and its stdout and stderr together.
std::pair<int, std::string> runNode(const std::string& name)
{
  const rviz_projector_test::RunResult result =
      rviz_projector_test::run({DEMO_CAMERA_BINARY, "__name:=" + name}, 20.0);
  return {result.status, result.out + result.err};
}

TEST(DemoCamera, NonsenseParametersStopTheNodeWithAReason)
{
  ros::param::set("/demo_camera_range/ambient", 1.5);
  ros::param::set("/demo_camera_range/D", std::vector<double>{0.1, 0.2, 0.3});
  ros::param::set("/demo_camera_range/exposure_delay", -1.0);
  ros::param::set("/demo_camera_range/supersampling", 9);
  ros::param::set("/demo_camera_range/projector_fx", -5.0);
  const auto range = runNode("demo_camera_range");
  EXPECT_EQ(range.first, 1) << range.second;
  for (const char* text : {"ambient must be in [0, 1]", "camera D must have 0, 4, 5", "~exposure_delay must be",
                           "supersampling must be 1..4", "projector fx and fy must be finite and positive"})
  {
    EXPECT_NE(range.second.find(text), std::string::npos) << text << " in: " << range.second;
  }
  ros::param::set("/demo_camera_board/board_pose", std::vector<double>{1.0, 0.0, 0.2});
  const auto board_pose = runNode("demo_camera_board");
  EXPECT_EQ(board_pose.first, 1) << board_pose.second;
  EXPECT_NE(board_pose.second.find("~board_pose must be [x, y, z, roll, pitch, yaw]"), std::string::npos)
      << board_pose.second;
  ros::param::set("/demo_camera_board_size/board_pose", std::vector<double>{1.0, 0.0, 0.2, 0.0, -0.7, 0.0});
  ros::param::set("/demo_camera_board_size/board_square", 2.0);
  const auto board_size = runNode("demo_camera_board_size");
  EXPECT_EQ(board_size.first, 1) << board_size.second;
  EXPECT_NE(board_size.second.find("the board needs 3..50 inner corners"), std::string::npos) << board_size.second;
  ros::param::set("/demo_camera_type/fx", std::string("wide"));
  ros::param::set("/demo_camera_type/projector_D", std::string("none"));
  const auto type = runNode("demo_camera_type");
  EXPECT_EQ(type.first, 1) << type.second;
  EXPECT_NE(type.second.find("~fx has the wrong type"), std::string::npos) << type.second;
  EXPECT_NE(type.second.find("~projector_D has the wrong type"), std::string::npos) << type.second;
}
}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "demo_camera_test");
  ros::NodeHandle nh;
  Harness instance;
  harness = &instance;
  const int result = RUN_ALL_TESTS();
  harness = nullptr;
  return result;
}
