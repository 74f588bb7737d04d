// calibrate_projector as a user runs it (the built binary, no ROS master): the --pattern template
// against crosshair pixels computed here by hand; a solve on points made from a known mount by an
// independent oracle (image_geometry + a hand-built rotation, test/nodes/mount_oracle.h): the
// printed projector.launch arguments, the residual table and mount.yaml; every bad input of the
// issue: exit status 1, a message naming the problem, and no file written; usage errors: status 2.

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <fstream>
#include <iomanip>
#include <vector>

#include "../support/child_process.h"
#include "mount_oracle.h"

namespace
{
using rviz_projector_test::TestMount;
using rviz_projector_test::TestPoint;

const std::string kBinary = CALIBRATE_PROJECTOR_BINARY;
const std::string kPa503w = std::string(CONFIG_DIR) + "/pa503w.yaml";

// config/pa503w.yaml: 1280 x 800. Crosshair centres over the central 80 %: u + 0.5 at 10 %, 50 %,
// 90 % of 1280 (128, 640, 1152), v + 0.5 at 10 %, 50 %, 90 % of 800 (80, 400, 720); a centre on a
// pixel boundary (u = 127.5) rounds half up. Ids row by row from the top left.
const std::vector<TestPoint> kPattern3x3 = {
    {1, 128, 80, {}}, {2, 640, 80, {}}, {3, 1152, 80, {}},    {4, 128, 400, {}}, {5, 640, 400, {}},
    {6, 1152, 400, {}}, {7, 128, 720, {}}, {8, 640, 720, {}}, {9, 1152, 720, {}},
};
// 2 rows x 4 columns: u + 0.5 = 1280 (0.1 + 0.8 k / 3) = 128, 469.33, 810.67, 1152 -> u = 128, 469,
// 810, 1152 (rounded); v + 0.5 = 80, 720.
const std::vector<TestPoint> kPattern2x4 = {
    {1, 128, 80, {}},  {2, 469, 80, {}},  {3, 810, 80, {}},  {4, 1152, 80, {}},
    {5, 128, 720, {}}, {6, 469, 720, {}}, {7, 810, 720, {}}, {8, 1152, 720, {}},
};

const TestMount kMount = {0.15, -0.05, 1.2, 0.04, 0.876, -0.12};

rviz_projector_test::RunResult calibrate(const std::vector<std::string>& args)
{
  std::vector<std::string> argv = {kBinary};
  argv.insert(argv.end(), args.begin(), args.end());
  return rviz_projector_test::run(argv);
}

/// The pattern's pixels with their floor points under `mount` (the oracle).
std::vector<TestPoint> floorPoints(const TestMount& mount, const std::vector<TestPoint>& pattern = kPattern3x3)
{
  image_geometry::PinholeCameraModel lens;
  EXPECT_TRUE(rviz_projector_test::lensFromFile(kPa503w, lens));
  const rviz_projector_test::TestPose pose = rviz_projector_test::opticalPoseByHand(mount);
  std::vector<TestPoint> points = pattern;
  for (TestPoint& p : points)
  {
    EXPECT_TRUE(rviz_projector_test::pixelOnPlane(lens, pose, p.u, p.v, 0.0, p.world)) << "id " << p.id;
  }
  return points;
}

/// "key:=value" pairs of the printed projector.launch arguments line.
std::map<std::string, std::string> launchArguments(const std::string& output)
{
  std::map<std::string, std::string> args;
  std::istringstream lines(output);
  std::string line;
  while (std::getline(lines, line))
  {
    if (line.find("parent_frame:=") == std::string::npos || line.find("or: ") != std::string::npos)
    {
      continue;
    }
    std::istringstream words(line);
    std::string word;
    while (words >> word)
    {
      const std::size_t sep = word.find(":=");
      if (sep != std::string::npos)
      {
        args[word.substr(0, sep)] = word.substr(sep + 2);
      }
    }
  }
  return args;
}

void expectMount(const TestMount& expected, const std::map<std::string, double>& actual, double tolerance)
{
  const std::map<std::string, double> want = {{"x", expected.x},       {"y", expected.y},
                                              {"z", expected.z},       {"roll", expected.roll},
                                              {"pitch", expected.pitch}, {"yaw", expected.yaw}};
  for (const auto& [key, value] : want)
  {
    ASSERT_EQ(1u, actual.count(key)) << key;
    EXPECT_NEAR(value, actual.at(key), tolerance) << key;
  }
}

struct Dir
{
  std::string path = rviz_projector_test::makeTempDir();
  std::string file(const std::string& name) const { return path + "/" + name; }
};

void expectPattern(const std::vector<TestPoint>& expected, const std::string& yaml)
{
  const YAML::Node doc = YAML::Load(yaml);
  EXPECT_EQ("base_link", doc["frame"].as<std::string>());
  const YAML::Node points = doc["points"];
  ASSERT_TRUE(points.IsSequence());
  ASSERT_EQ(expected.size(), points.size()) << yaml;
  for (std::size_t i = 0; i < expected.size(); ++i)
  {
    EXPECT_EQ(expected[i].id, points[i]["id"].as<int>()) << i;
    EXPECT_EQ(expected[i].u, points[i]["u"].as<double>()) << "id " << expected[i].id;
    EXPECT_EQ(expected[i].v, points[i]["v"].as<double>()) << "id " << expected[i].id;
    EXPECT_TRUE(points[i]["x"].IsNull()) << "x left for the user, id " << expected[i].id;
    EXPECT_TRUE(points[i]["y"].IsNull()) << "y left for the user, id " << expected[i].id;
  }
}
}  // namespace

// --- --pattern --------------------------------------------------------------------------------

TEST(CalibrateProjectorPattern, Default3x3OfThePa503w)
{
  const auto result = calibrate({"--pattern", "--camera-info", kPa503w});
  ASSERT_EQ(0, result.status) << result.err;
  EXPECT_NE(std::string::npos, result.out.find("# ")) << "a comment header telling what to fill in";
  EXPECT_NE(std::string::npos, result.out.find("x: null, y: null"));
  expectPattern(kPattern3x3, result.out);
}

TEST(CalibrateProjectorPattern, TwoRowsFourColumns)
{
  const auto result = calibrate({"--pattern", "--camera-info", kPa503w, "--rows", "2", "--cols", "4"});
  ASSERT_EQ(0, result.status) << result.err;
  expectPattern(kPattern2x4, result.out);
}

TEST(CalibrateProjectorPattern, UnfilledTemplateIsRefusedByIds)
{
  Dir dir;
  const auto pattern = calibrate({"--pattern", "--camera-info", kPa503w});
  ASSERT_EQ(0, pattern.status) << pattern.err;
  // The user filled in all but crosshairs 2 and 7.
  std::string text = pattern.out;
  const std::vector<TestPoint> points = floorPoints(kMount);
  for (const TestPoint& p : points)
  {
    if (p.id == 2 || p.id == 7)
    {
      continue;
    }
    const std::string line = "{id: " + std::to_string(p.id) + ",";
    const std::size_t at = text.find(line);
    ASSERT_NE(std::string::npos, at) << line;
    const std::size_t null = text.find("x: null, y: null", at);
    text.replace(null, 16, "x: " + std::to_string(p.world[0]) + ", y: " + std::to_string(p.world[1]));
  }
  rviz_projector_test::writeFile(dir.file("points.yaml"), text);
  const auto result = calibrate({"--camera-info", kPa503w, "--points", dir.file("points.yaml"), "--output",
                                 dir.file("mount.yaml")});
  EXPECT_EQ(1, result.status) << result.out << result.err;
  EXPECT_NE(std::string::npos, result.err.find("points 2, 7 are not measured yet")) << result.err;
  EXPECT_FALSE(rviz_projector_test::fileExists(dir.file("mount.yaml")));
}

// --- solving --------------------------------------------------------------------------------

TEST(CalibrateProjectorSolve, ExactPointsGiveTheMountAsLaunchArgumentsAndMountFile)
{
  Dir dir;
  rviz_projector_test::writeFile(dir.file("points.yaml"), rviz_projector_test::pointsYaml("base_link",
                                                                                          floorPoints(kMount)));
  const auto result = calibrate({"--camera-info", kPa503w, "--points", dir.file("points.yaml"), "--output",
                                 dir.file("mount.yaml")});
  ASSERT_EQ(0, result.status) << result.out << result.err;

  const auto args = launchArguments(result.out);
  ASSERT_EQ(1u, args.count("parent_frame")) << result.out;
  EXPECT_EQ("base_link", args.at("parent_frame"));
  std::map<std::string, double> printed;
  for (const char* key : {"x", "y", "z", "roll", "pitch", "yaw"})
  {
    ASSERT_EQ(1u, args.count(key)) << key << " in\n" << result.out;
    printed[key] = std::stod(args.at(key));
  }
  expectMount(kMount, printed, 2e-6);  // printed with 6 decimals

  const YAML::Node mount = YAML::LoadFile(dir.file("mount.yaml"));
  EXPECT_EQ("base_link", mount["parent_frame"].as<std::string>());
  std::map<std::string, double> written;
  for (const char* key : {"x", "y", "z", "roll", "pitch", "yaw"})
  {
    written[key] = mount[key].as<double>();
  }
  expectMount(kMount, written, 1e-6);
  EXPECT_LT(mount["rms_px"].as<double>(), 0.01);
  EXPECT_LT(mount["rms_mm"].as<double>(), 0.05);
  EXPECT_EQ(0u, mount["outliers"].size());
  ASSERT_EQ(9u, mount["residuals"].size());
  for (std::size_t i = 0; i < 9; ++i)
  {
    EXPECT_EQ(static_cast<int>(i + 1), mount["residuals"][i]["id"].as<int>());
    EXPECT_LT(mount["residuals"][i]["px"].as<double>(), 0.01);
    EXPECT_LT(mount["residuals"][i]["mm"].as<double>(), 0.05);
  }

  // The residual table: a row per point (id, px, mm, outlier no).
  for (int id = 1; id <= 9; ++id)
  {
    std::ostringstream row;
    row << "\n" << std::string(id < 10 ? 6 : 5, ' ') << id << "     0.000      0.00  no\n";
    EXPECT_NE(std::string::npos, result.out.find(row.str())) << "row of point " << id << " in\n" << result.out;
  }
  EXPECT_NE(std::string::npos, result.out.find("RMS")) << result.out;
  EXPECT_NE(std::string::npos, result.out.find("Outliers: none")) << result.out;
  EXPECT_NE(std::string::npos, result.out.find("2 m ahead")) << "expected floor error\n" << result.out;
}

TEST(CalibrateProjectorSolve, PixelsFromThePatternByIdAndAnotherFrame)
{
  Dir dir;
  const TestMount mount = {-0.3, 0.2, 0.5, -0.08, 1.2, 0.15};
  // No u, v in the file: they come from the 2x4 pattern by id.
  rviz_projector_test::writeFile(dir.file("points.yaml"),
                                 rviz_projector_test::pointsYaml("robot_top", floorPoints(mount, kPattern2x4),
                                                                 false));
  const auto result = calibrate({"--camera-info", kPa503w, "--points", dir.file("points.yaml"), "--rows", "2",
                                 "--cols", "4", "--output", dir.file("mount.yaml")});
  ASSERT_EQ(0, result.status) << result.out << result.err;
  const YAML::Node written = YAML::LoadFile(dir.file("mount.yaml"));
  EXPECT_EQ("robot_top", written["parent_frame"].as<std::string>());
  std::map<std::string, double> values;
  for (const char* key : {"x", "y", "z", "roll", "pitch", "yaw"})
  {
    values[key] = written[key].as<double>();
  }
  expectMount(mount, values, 1e-6);
  EXPECT_EQ("robot_top", launchArguments(result.out)["parent_frame"]);
}

TEST(CalibrateProjectorSolve, OutlierIsNamedAndRejected)
{
  Dir dir;
  std::vector<TestPoint> points = floorPoints(kMount);
  points[4].world[0] += 0.10;  // crosshair 5 measured 10 cm off
  rviz_projector_test::writeFile(dir.file("points.yaml"), rviz_projector_test::pointsYaml("base_link", points));
  const auto result = calibrate({"--camera-info", kPa503w, "--points", dir.file("points.yaml"), "--output",
                                 dir.file("mount.yaml")});
  ASSERT_EQ(0, result.status) << result.out << result.err;
  const YAML::Node written = YAML::LoadFile(dir.file("mount.yaml"));
  ASSERT_EQ(1u, written["outliers"].size()) << result.out;
  EXPECT_EQ(5, written["outliers"][0].as<int>());
  EXPECT_NE(std::string::npos, result.out.find("Outliers (rejected")) << result.out;
  EXPECT_NE(std::string::npos, result.out.find("  yes\n")) << result.out;
  std::map<std::string, double> values;
  for (const char* key : {"x", "y", "z", "roll", "pitch", "yaw"})
  {
    values[key] = written[key].as<double>();
  }
  expectMount(kMount, values, 1e-5);
}

/// 9 floor points and 3 off the floor (boxes 0.3 .. 0.5 m high), exact, written as a points file:
/// enough for --fit-intrinsics.
void writeFloorAndBoxPoints(const std::string& path)
{
  std::vector<TestPoint> points = floorPoints(kMount);
  image_geometry::PinholeCameraModel lens;
  ASSERT_TRUE(rviz_projector_test::lensFromFile(kPa503w, lens));
  const std::vector<TestPoint> boxes = {{10, 384, 240, {0, 0, 0.4}}, {11, 896, 560, {0, 0, 0.3}},
                                        {12, 640, 160, {0, 0, 0.5}}};
  for (TestPoint p : boxes)
  {
    ASSERT_TRUE(rviz_projector_test::pixelOnPlane(lens, rviz_projector_test::opticalPoseByHand(kMount), p.u, p.v,
                                                  p.world[2], p.world));
    points.push_back(p);
  }
  rviz_projector_test::writeFile(path, rviz_projector_test::pointsYaml("base_link", points));
}

TEST(CalibrateProjectorSolve, FitIntrinsicsWritesTheFittedCalibration)
{
  Dir dir;
  ASSERT_NO_FATAL_FAILURE(writeFloorAndBoxPoints(dir.file("points.yaml")));
  const auto result =
      calibrate({"--camera-info", kPa503w, "--points", dir.file("points.yaml"), "--fit-intrinsics", "--tape-error",
                 "1", "--output-calibration", dir.file("cal.yaml"), "--output", dir.file("mount.yaml")});
  ASSERT_EQ(0, result.status) << result.out << result.err;
  EXPECT_NE(std::string::npos, result.out.find("Fitted intrinsics")) << result.out;
  // The written calibration, read back by the oracle's own loader: config/pa503w.yaml's numbers.
  image_geometry::PinholeCameraModel fitted;
  ASSERT_TRUE(rviz_projector_test::lensFromFile(dir.file("cal.yaml"), fitted)) << rviz_projector_test::readFile(
      dir.file("cal.yaml"));
  EXPECT_EQ(1280u, fitted.cameraInfo().width);
  EXPECT_EQ(800u, fitted.cameraInfo().height);
  EXPECT_NEAR(1900.0, fitted.fx(), 0.1);
  EXPECT_NEAR(1900.0, fitted.fy(), 0.1);
  EXPECT_NEAR(640.0, fitted.cx(), 0.1);
  EXPECT_NEAR(817.0, fitted.cy(), 0.1);
  EXPECT_NEAR(1900.0, fitted.cameraInfo().K[0], 0.1) << "K as well as P";
  EXPECT_NEAR(817.0, fitted.cameraInfo().K[5], 0.1) << "K as well as P";
  const YAML::Node mount = YAML::LoadFile(dir.file("mount.yaml"));
  EXPECT_NEAR(kMount.pitch, mount["pitch"].as<double>(), 1e-5);
}

/// A copy of config/pa503w.yaml with plumb_bob D = [k1, k2, 0, 0, 0].
std::string distortedPa503w(double k1, double k2)
{
  std::string yaml = rviz_projector_test::readFile(kPa503w);
  const std::string from = "data: [0.0, 0.0, 0.0, 0.0, 0.0]";
  EXPECT_NE(std::string::npos, yaml.find(from));
  std::ostringstream d;
  d << std::setprecision(17) << "data: [" << k1 << ", " << k2 << ", 0.0, 0.0, 0.0]";
  yaml.replace(yaml.find(from), from.size(), d.str());
  return yaml;
}

TEST(CalibrateProjectorSolve, FitDistortionWritesK1K2InTheCalibration)
{
  // The true lens: the PA503W with k1 = -0.1, k2 = 0.02. The 5 x 5 crosshairs' floor points by the
  // oracle: image_geometry's rectifyPoint (cv::undistortPoints) of each raw crosshair pixel, its ray.
  Dir dir;
  rviz_projector_test::writeFile(dir.file("true.yaml"), distortedPa503w(-0.1, 0.02));
  image_geometry::PinholeCameraModel truth;
  ASSERT_TRUE(rviz_projector_test::lensFromFile(dir.file("true.yaml"), truth));
  std::vector<TestPoint> points;
  const rviz_projector_test::TestPose pose = rviz_projector_test::opticalPoseByHand(kMount);
  for (int r = 0; r < 5; ++r)
  {
    for (int c = 0; c < 5; ++c)
    {
      // The 5 x 5 pattern: u + 0.5 = 1280 (0.1 + 0.2 c), v + 0.5 = 800 (0.1 + 0.2 r), on pixel
      // boundaries, rounded half up: u = 128, 384, ..., 1152, v = 80, 240, ..., 720.
      TestPoint p{5 * r + c + 1, std::round(1280 * (0.1 + 0.2 * c)), std::round(800 * (0.1 + 0.2 * r)), {}};
      const cv::Point2d rectified = truth.rectifyPoint(cv::Point2d(p.u, p.v));
      ASSERT_TRUE(rviz_projector_test::pixelOnPlane(truth, pose, rectified.x, rectified.y, 0.0, p.world));
      points.push_back(p);
    }
  }
  rviz_projector_test::writeFile(dir.file("points.yaml"), rviz_projector_test::pointsYaml("base_link", points));
  // The prior calibration has no distortion (config/pa503w.yaml).
  const auto result = calibrate({"--camera-info", kPa503w, "--points", dir.file("points.yaml"), "--rows", "5",
                                 "--cols", "5", "--fit-distortion", "--tape-error", "1", "--output-calibration",
                                 dir.file("cal.yaml"), "--output", dir.file("mount.yaml")});
  ASSERT_EQ(0, result.status) << result.out << result.err;
  EXPECT_NE(std::string::npos, result.out.find("Fitted distortion (plumb_bob, 1 sigma): k1 -0.10000")) << result.out;

  // Read back by the oracle's loader: D and the model; K and P unchanged.
  image_geometry::PinholeCameraModel fitted;
  ASSERT_TRUE(rviz_projector_test::lensFromFile(dir.file("cal.yaml"), fitted))
      << rviz_projector_test::readFile(dir.file("cal.yaml"));
  EXPECT_EQ("plumb_bob", fitted.cameraInfo().distortion_model);
  ASSERT_EQ(5u, fitted.cameraInfo().D.size());
  EXPECT_NEAR(-0.1, fitted.cameraInfo().D[0], 1e-5);
  EXPECT_NEAR(0.02, fitted.cameraInfo().D[1], 1e-4);
  EXPECT_EQ(0.0, fitted.cameraInfo().D[2]);
  EXPECT_EQ(0.0, fitted.cameraInfo().D[3]);
  EXPECT_EQ(0.0, fitted.cameraInfo().D[4]);
  EXPECT_EQ(1900.0, fitted.fx());
  EXPECT_EQ(817.0, fitted.cy());
  EXPECT_EQ(817.0, fitted.cameraInfo().K[5]);
  std::map<std::string, double> written;
  const YAML::Node mount = YAML::LoadFile(dir.file("mount.yaml"));
  for (const char* key : {"x", "y", "z", "roll", "pitch", "yaw"})
  {
    written[key] = mount[key].as<double>();
  }
  expectMount(kMount, written, 1e-5);

  // calibrate_projector's own reader takes the written file back.
  const auto again = calibrate({"--pattern", "--camera-info", dir.file("cal.yaml")});
  EXPECT_EQ(0, again.status) << again.err;

  // 9 crosshairs measured to 3 mm cannot pin k1: an error, nothing written.
  std::vector<TestPoint> nine;
  for (const TestPoint& p : points)
  {
    if (p.id % 2 == 1)  // 1, 3, 5, 11, 13, 15, 21, 23, 25: the 3 x 3 over the same span
    {
      if ((p.id - 1) / 5 % 2 == 0)
      {
        nine.push_back(p);
      }
    }
  }
  ASSERT_EQ(9u, nine.size());
  rviz_projector_test::writeFile(dir.file("nine.yaml"), rviz_projector_test::pointsYaml("base_link", nine));
  const auto weak = calibrate({"--camera-info", kPa503w, "--points", dir.file("nine.yaml"), "--rows", "5", "--cols",
                               "5", "--fit-distortion", "--output-calibration", dir.file("cal9.yaml")});
  EXPECT_EQ(1, weak.status) << weak.out << weak.err;
  EXPECT_NE(std::string::npos, weak.err.find("cannot pin the distortion")) << weak.err;
  EXPECT_FALSE(rviz_projector_test::fileExists(dir.file("cal9.yaml")));
}

TEST(CalibrateProjectorSolve, APointAboveTheProjectorIsAnOutlier)
{
  // Issue 23, defect 4: a z its crosshair's ray cannot reach (typed in cm, or the wrong plane) is
  // flagged like a wrong x or y; it used to fail the whole solve.
  Dir dir;
  std::string yaml = rviz_projector_test::pointsYaml("base_link", floorPoints(kMount));
  const std::string from = "{id: 5, u: 640, v: 400, x: ";
  ASSERT_NE(std::string::npos, yaml.find(from)) << yaml;
  yaml.replace(yaml.find(from), from.size(), "{id: 5, u: 640, v: 400, z: 3.0, x: ");
  rviz_projector_test::writeFile(dir.file("points.yaml"), yaml);
  const auto result = calibrate({"--camera-info", kPa503w, "--points", dir.file("points.yaml")});
  ASSERT_EQ(0, result.status) << result.out << result.err;
  EXPECT_NE(std::string::npos, result.out.find("1 rejected as outliers")) << result.out;
  EXPECT_NE(std::string::npos, result.out.find("5 (its crosshair's ray cannot reach the point's z: check z)"))
      << result.out;
}

TEST(CalibrateProjectorSolve, OutputFilesAreWrittenAllOrNothing)
{
  // Issue 23, defect 5: mount.yaml used to be written before the calibration file failed.
  Dir dir;
  ASSERT_NO_FATAL_FAILURE(writeFloorAndBoxPoints(dir.file("points.yaml")));
  const auto result = calibrate({"--camera-info", kPa503w, "--points", dir.file("points.yaml"), "--fit-intrinsics",
                                 "--tape-error", "1", "--output", dir.file("mount.yaml"), "--output-calibration",
                                 dir.file("no_such_directory/cal.yaml")});
  EXPECT_NE(0, result.status) << result.out << result.err;
  EXPECT_NE(std::string::npos, result.err.find("no_such_directory/cal.yaml")) << result.err;
  EXPECT_FALSE(std::ifstream(dir.file("mount.yaml")).good()) << "mount.yaml written although the set failed";
  EXPECT_FALSE(std::ifstream(dir.file("mount.yaml.tmp")).good()) << "a temporary file was left behind";
}

TEST(CalibrateProjectorSolve, FitIntrinsicsFromFloorPointsAloneIsRefused)
{
  Dir dir;
  rviz_projector_test::writeFile(dir.file("points.yaml"), rviz_projector_test::pointsYaml("base_link",
                                                                                          floorPoints(kMount)));
  const auto result = calibrate({"--camera-info", kPa503w, "--points", dir.file("points.yaml"), "--fit-intrinsics",
                                 "--output-calibration", dir.file("cal.yaml"), "--output", dir.file("mount.yaml")});
  EXPECT_EQ(1, result.status) << result.out << result.err;
  EXPECT_NE(std::string::npos, result.err.find("off the floor")) << result.err;
  EXPECT_FALSE(rviz_projector_test::fileExists(dir.file("cal.yaml")));
  EXPECT_FALSE(rviz_projector_test::fileExists(dir.file("mount.yaml")));
}

// --- bad input: status 1, the problem named, nothing written ---------------------------------------

struct BadInput
{
  std::string name;
  std::string points_yaml;  ///< "" = use the calibration's problem instead
  std::string expected;     ///< substring of stderr
  std::string camera_info = kPa503w;
};

class CalibrateProjectorBadInput : public ::testing::TestWithParam<BadInput>
{
};

std::string goodPointsWith(const std::string& replace, const std::string& by)
{
  std::string text = rviz_projector_test::pointsYaml("base_link", floorPoints(kMount));
  const std::size_t at = text.find(replace);
  EXPECT_NE(std::string::npos, at) << replace;
  return at == std::string::npos ? text : text.replace(at, replace.size(), by);
}

std::string firstPoints(std::size_t count)
{
  std::vector<TestPoint> points = floorPoints(kMount);
  points.resize(count);
  return rviz_projector_test::pointsYaml("base_link", points);
}

TEST_P(CalibrateProjectorBadInput, ExitOneWithMessageAndNoOutput)
{
  const BadInput& bad = GetParam();
  Dir dir;
  rviz_projector_test::writeFile(dir.file("points.yaml"), bad.points_yaml);
  const auto result = calibrate({"--camera-info", bad.camera_info, "--points", dir.file("points.yaml"), "--output",
                                 dir.file("mount.yaml")});
  EXPECT_EQ(1, result.status) << result.out << result.err;
  EXPECT_NE(std::string::npos, result.err.find("calibrate_projector: error: ")) << result.err;
  EXPECT_NE(std::string::npos, result.err.find(bad.expected)) << "missing '" << bad.expected << "' in\n"
                                                              << result.err;
  EXPECT_EQ("", result.out) << "nothing printed as a solution";
  EXPECT_FALSE(rviz_projector_test::fileExists(dir.file("mount.yaml")));
  EXPECT_FALSE(rviz_projector_test::fileExists(dir.file("mount.yaml.tmp")));
}

std::vector<BadInput> badInputs()
{
  const std::string good = rviz_projector_test::pointsYaml("base_link", floorPoints(kMount));
  // Lines of the good file, to build collinear and out-of-image sets from.
  std::vector<TestPoint> row = floorPoints(kMount);
  std::vector<TestPoint> collinear = {row[3], row[4], row[5]};  // the middle row ...
  TestPoint extra = row[4];                                     // ... and one more point on it
  extra.id = 10;
  extra.u = 384;
  image_geometry::PinholeCameraModel lens;
  rviz_projector_test::lensFromFile(kPa503w, lens);
  rviz_projector_test::pixelOnPlane(lens, rviz_projector_test::opticalPoseByHand(kMount), extra.u, extra.v, 0.0,
                                    extra.world);
  collinear.push_back(extra);
  const std::string calibration = std::string(CALIBRATION_TEST_DIR) + "/";
  return {
      {"MalformedYaml", "frame: base_link\npoints:\n  - {id: 1, u: 128, v: 80, x: 1.0\n", "not valid YAML"},
      {"Empty", "", "the file is empty"},
      {"NoFrame", "points: []\n", "missing field 'frame'"},
      {"PointsNotAList", "frame: base_link\npoints: 3\n", "field 'points' must be a list"},
      {"UnknownField", goodPointsWith("{id: 3,", "{id: 3, w: 1,"), "point 3 (entry 3 of 'points'): unknown field 'w'"},
      {"NotANumber", goodPointsWith("{id: 4, u: 128, v: 400, x: ", "{id: 4, u: 128, v: 400, x: abc, z: "),
       "point 4 (entry 4 of 'points'): 'x' is not a number (got 'abc')"},
      {"NaN", goodPointsWith("{id: 3, u: 1152, v: 80, x: ", "{id: 3, u: 1152, v: 80, x: .nan, z: "),
       "point 3 (entry 3 of 'points'): 'x' is not finite"},
      {"Inf", goodPointsWith("{id: 6, u: 1152, v: 400, x: ", "{id: 6, u: 1152, v: 400, z: .inf, x: "),
       "point 6 (entry 6 of 'points'): 'z' is not finite"},
      {"NaNPixel", goodPointsWith("{id: 2, u: 640,", "{id: 2, u: .nan,"), "'u' is not finite"},
      {"DuplicateId", goodPointsWith("{id: 8,", "{id: 2,"), "duplicate id 2 (entries 2 and 8 of 'points')"},
      {"UnknownId", goodPointsWith("{id: 9, u: 1152, v: 720,", "{id: 12,"), "unknown id 12"},
      {"OnlyU", goodPointsWith("{id: 9, u: 1152, v: 720,", "{id: 9, u: 1152,"), "give both 'u' and 'v'"},
      {"Millimetres", goodPointsWith("{id: 5, u: 640, v: 400, x: ", "{id: 5, u: 640, v: 400, x: 2013, z: "),
       "point 5 (entry 5 of 'points'): 'x' is 2013, which looks like millimetres"},
      {"ThreePoints", firstPoints(3), "need at least 4 points, got 3"},
      {"Collinear", rviz_projector_test::pointsYaml("base_link", collinear), "collinear"},
      {"OutsideTheImage", goodPointsWith("{id: 1, u: 128,", "{id: 1, u: 1400,"), "outside"},
      {"CalibrationFailsTheDisplaysCheck", good, "unusable calibration", calibration + "zero_focal_length.yaml"},
      {"CalibrationMissing", good, "file not found", calibration + "no_such_file.yaml"},
      {"CalibrationMalformed", good, "missing field 'camera_matrix'", calibration + "missing_camera_matrix.yaml"},
  };
}

INSTANTIATE_TEST_SUITE_P(Each, CalibrateProjectorBadInput, ::testing::ValuesIn(badInputs()),
                         [](const ::testing::TestParamInfo<BadInput>& info) { return info.param.name; });

TEST(CalibrateProjectorBadInputs, NoSuchPointsFile)
{
  Dir dir;
  const auto result = calibrate({"--camera-info", kPa503w, "--points", dir.file("missing.yaml"), "--output",
                                 dir.file("mount.yaml")});
  EXPECT_EQ(1, result.status);
  EXPECT_NE(std::string::npos, result.err.find("missing.yaml: cannot be read")) << result.err;
  EXPECT_FALSE(rviz_projector_test::fileExists(dir.file("mount.yaml")));
}

TEST(CalibrateProjectorBadInputs, PatternWithAnUnusableCalibration)
{
  const auto result =
      calibrate({"--pattern", "--camera-info", std::string(CALIBRATION_TEST_DIR) + "/zero_focal_length.yaml"});
  EXPECT_EQ(1, result.status);
  EXPECT_EQ("", result.out);
  EXPECT_NE(std::string::npos, result.err.find("unusable calibration")) << result.err;
}

TEST(CalibrateProjectorBadInputs, ClickedPointsWithoutARosMaster)
{
  Dir dir;
  const auto result = rviz_projector_test::run({"/usr/bin/env", "ROS_MASTER_URI=http://127.0.0.1:1", kBinary,
                                                "--clicked-points", "--camera-info", kPa503w, "--points-out",
                                                dir.file("points.yaml")});
  EXPECT_EQ(1, result.status) << result.out << result.err;
  EXPECT_NE(std::string::npos, result.err.find("no ROS master at http://127.0.0.1:1")) << result.err;
  EXPECT_FALSE(rviz_projector_test::fileExists(dir.file("points.yaml")));
}

// --- usage: status 2 ----------------------------------------------------------------------------

TEST(CalibrateProjectorUsage, BadCommandLinesExitTwo)
{
  const std::vector<std::vector<std::string>> command_lines = {
      {},
      {"--points", "points.yaml"},
      {"--camera-info", kPa503w},
      {"--pattern", "--camera-info", kPa503w, "--rows", "0"},
      {"--pattern", "--camera-info", kPa503w, "--cols", "x"},
      {"--pattern", "--camera-info", kPa503w, "--rows", "11"},
      {"--pattern", "--camera-info", kPa503w, "--points", "points.yaml"},
      {"--camera-info", kPa503w, "--points", "points.yaml", "--bogus"},
      {"--camera-info", kPa503w, "--points", "points.yaml", "--output-calibration", "cal.yaml"},
      {"--camera-info", kPa503w, "--points", "points.yaml", "--fit-intrinsics", "--fit-distortion"},
      {"--pattern", "--camera-info", kPa503w, "--fit-distortion"},
      {"--clicked-points", "--camera-info", kPa503w},
      {"--camera-info"},
      {"--camera-info", kPa503w, "--points", "points.yaml", "--tape-error", "0"},
      {"--camera-info", kPa503w, "--points", "points.yaml", "--tape-error", "3mm"},
      // --camera (issue 24)
      {"--camera", "--camera-info", kPa503w, "--settle", "6"},
      {"--camera", "--camera-info", kPa503w, "--settle", "-1"},
      {"--camera", "--camera-info", kPa503w, "--points", "points.yaml"},
      {"--camera", "--camera-info", kPa503w, "--fit-distortion"},
      {"--camera", "--pattern", "--camera-info", kPa503w},
      {"--camera", "--camera-info", kPa503w, "--image", ""},
      {"--camera-info", kPa503w, "--points", "points.yaml", "--settle", "0.2"},
      {"--camera-info", kPa503w, "--points", "points.yaml", "--keep-distortion"},
      {"--camera-info", kPa503w, "--points", "points.yaml", "--board", "7x5:0.06"},
      {"--camera", "--camera-info", kPa503w, "--board", "7x5"},
      {"--camera", "--camera-info", kPa503w, "--board", "7x5:60"},
      {"--camera", "--camera-info", kPa503w, "--board"},
  };
  for (const auto& args : command_lines)
  {
    const auto result = calibrate(args);
    std::string joined;
    for (const std::string& arg : args)
    {
      joined += arg + " ";
    }
    EXPECT_EQ(2, result.status) << joined << "\n" << result.err;
    EXPECT_NE(std::string::npos, result.err.find("Usage:")) << joined;
  }
  const auto help = calibrate({"--help"});
  EXPECT_EQ(0, help.status);
  EXPECT_NE(std::string::npos, help.out.find("--pattern"));
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
