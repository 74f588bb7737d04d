// projector_info_publisher: a good file is published as the CameraInfo it describes, stamped with
// the optical frame; a missing, malformed or unusable file stops the node with exit status 1 and
// a ROS_FATAL naming the file and the problem. The config/ files shipped with the package load
// without a warning.
//
// projector_info_publisher.test starts two instances: one on test/nodes/calibration/good.yaml
// (remapped topic), one on package://rviz_projector/config/pa503w.yaml (~topic parameter). The
// bad-file cases run the node binary directly, with the rostest master, and read its output.

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <ros/topic.h>
#include <sensor_msgs/CameraInfo.h>

#include <string>
#include <vector>

#include "../support/child_process.h"
#include "rviz_projector/calibration/calibration_file.h"

namespace
{
/// The node's exit status and its stdout and stderr together.
struct NodeRun
{
  int exit_status = -1;
  std::string output;
};

/// Runs the node binary with `arguments` (no shell), at most 20 s.
NodeRun runNode(const std::vector<std::string>& arguments)
{
  static int run = 0;
  std::vector<std::string> argv{PROJECTOR_INFO_PUBLISHER_BINARY,
                                "__name:=projector_info_publisher_run_" + std::to_string(run++)};
  argv.insert(argv.end(), arguments.begin(), arguments.end());
  const rviz_projector_test::RunResult result = rviz_projector_test::run(argv, 20.0);
  return {result.status, result.out + result.err};
}

NodeRun runNodeOnFile(const std::string& file)
{
  return runNode({"_calibration_file:=" + file});
}

std::string testFile(const std::string& name)
{
  return std::string(CALIBRATION_TEST_DIR) + "/" + name;
}

void expectArray(const std::vector<double>& expected, const double* actual, const std::string& what)
{
  for (std::size_t i = 0; i < expected.size(); ++i)
  {
    EXPECT_DOUBLE_EQ(expected[i], actual[i]) << what << "[" << i << "]";
  }
}

/// The node must fail with status 1 and a fatal message holding every one of `expected`.
void expectFailure(const NodeRun& result, const std::vector<std::string>& expected)
{
  EXPECT_EQ(1, result.exit_status) << result.output;
  EXPECT_NE(std::string::npos, result.output.find("projector_info_publisher: ")) << result.output;
  EXPECT_NE(std::string::npos, result.output.find("FATAL")) << result.output;
  for (const std::string& text : expected)
  {
    EXPECT_NE(std::string::npos, result.output.find(text)) << "missing '" << text << "' in:\n" << result.output;
  }
}
}  // namespace

// --- the running node -------------------------------------------------------------------------

TEST(ProjectorInfoPublisher, PublishesGoodFileLatchedWithOpticalFrame)
{
  const sensor_msgs::CameraInfo::ConstPtr info =
      ros::topic::waitForMessage<sensor_msgs::CameraInfo>("/test_projector/camera_info", ros::Duration(15.0));
  ASSERT_TRUE(info != nullptr) << "no CameraInfo on /test_projector/camera_info";
  EXPECT_EQ("test_optical_frame", info->header.frame_id);
  EXPECT_FALSE(info->header.stamp.isZero());
  EXPECT_EQ(1280u, info->width);
  EXPECT_EQ(800u, info->height);
  EXPECT_EQ("plumb_bob", info->distortion_model);
  ASSERT_EQ(5u, info->D.size());
  expectArray({0, 0, 0, 0, 0}, info->D.data(), "D");
  expectArray({1500, 0, 639.5, 0, 1500, 399.5, 0, 0, 1}, info->K.data(), "K");
  expectArray({1, 0, 0, 0, 1, 0, 0, 0, 1}, info->R.data(), "R");
  expectArray({1500, 0, 639.5, 0, 0, 1500, 399.5, 0, 0, 0, 1, 0}, info->P.data(), "P");
}

TEST(ProjectorInfoPublisher, TopicParameterAndPackageUrl)
{
  // The reference projector's file, found through package://, published on ~topic.
  const sensor_msgs::CameraInfo::ConstPtr info =
      ros::topic::waitForMessage<sensor_msgs::CameraInfo>("/test_projector/pa503w_info", ros::Duration(15.0));
  ASSERT_TRUE(info != nullptr) << "no CameraInfo on /test_projector/pa503w_info";
  EXPECT_EQ("pa503w_optical_frame", info->header.frame_id);
  EXPECT_EQ(1280u, info->width);
  EXPECT_EQ(800u, info->height);
  expectArray({1900, 0, 640, 0, 1900, 817, 0, 0, 1}, info->K.data(), "K");
  expectArray({1900, 0, 640, 0, 0, 1900, 817, 0, 0, 0, 1, 0}, info->P.data(), "P");
}

TEST(ProjectorInfoPublisher, RelativePathIsTakenFromTheBaseDirectory)
{
  // Issue 23: `projector.launch calibration_file:=CAL.yaml` failed, roslaunch running the node in
  // ~/.ros; the launch file now passes its working directory, as it does for mount_file.
  const sensor_msgs::CameraInfo::ConstPtr info =
      ros::topic::waitForMessage<sensor_msgs::CameraInfo>("/test_projector/relative_info", ros::Duration(15.0));
  ASSERT_TRUE(info != nullptr) << "no CameraInfo on /test_projector/relative_info";
  EXPECT_EQ("relative_optical_frame", info->header.frame_id);
  expectArray({1500, 0, 639.5, 0, 1500, 399.5, 0, 0, 1}, info->K.data(), "K");
}

// --- bad input: exit status 1, the file and the problem named -------------------------------------

TEST(ProjectorInfoPublisher, MissingFile)
{
  expectFailure(runNodeOnFile("/nonexistent/rviz_projector/projector.yaml"),
                {"/nonexistent/rviz_projector/projector.yaml: file not found"});
}

TEST(ProjectorInfoPublisher, RelativeMissingFileExplainsTheWorkingDirectory)
{
  expectFailure(runNodeOnFile("my_projector.yaml"),
                {"my_projector.yaml: file not found", "relative path", "working directory"});
}

TEST(ProjectorInfoPublisher, ParameterNotSet)
{
  expectFailure(runNode({}), {"calibration_file is not set"});
}

TEST(ProjectorInfoPublisher, UnknownPackage)
{
  expectFailure(runNodeOnFile("package://no_such_package_rviz_projector/p.yaml"),
                {"package://no_such_package_rviz_projector/p.yaml: package 'no_such_package_rviz_projector' not found"});
}

TEST(ProjectorInfoPublisher, MissingField)
{
  const std::string file = testFile("missing_camera_matrix.yaml");
  expectFailure(runNodeOnFile(file), {file + ": missing field 'camera_matrix'"});
}

TEST(ProjectorInfoPublisher, ZeroWidth)
{
  const std::string file = testFile("zero_width.yaml");
  expectFailure(runNodeOnFile(file), {file + ": image_width must be > 0 (got 0)"});
}

TEST(ProjectorInfoPublisher, MatrixWithTooFewNumbers)
{
  const std::string file = testFile("short_camera_matrix.yaml");
  expectFailure(runNodeOnFile(file), {file + ": field 'camera_matrix': 'data' has 8 numbers, expected rows x cols = "
                                             "3 x 3 = 9"});
}

TEST(ProjectorInfoPublisher, NotANumber)
{
  const std::string file = testFile("not_a_number.yaml");
  expectFailure(runNodeOnFile(file),
                {file + ": field 'projection_matrix': data[5] is not a number (got 'fifteen hundred')"});
}

TEST(ProjectorInfoPublisher, YamlSyntaxError)
{
  const std::string file = testFile("bad_syntax.yaml");
  expectFailure(runNodeOnFile(file), {file + ": not valid YAML: line "});
}

TEST(ProjectorInfoPublisher, EmptyFile)
{
  const std::string file = testFile("empty.yaml");
  expectFailure(runNodeOnFile(file), {file + ": the file is empty"});
}

TEST(ProjectorInfoPublisher, WrongFileType)
{
  const std::string file = testFile("wrong_extension.txt");
  expectFailure(runNodeOnFile(file), {file + ": unsupported file type '.txt'"});
}

TEST(ProjectorInfoPublisher, UnusableLensRefusedWithTheCoresReason)
{
  const std::string file = testFile("zero_focal_length.yaml");
  expectFailure(runNodeOnFile(file),
                {file + ": unusable calibration: focal length in P is not positive (fx = 0, fy = 0)"});
}

// --- the loader on the files shipped in config/ ---------------------------------------------------

TEST(CalibrationFile, ShippedFilesLoadWithoutWarnings)
{
  for (const char* name : {"pa503w.yaml", "projector_template.yaml", "demo_projector.yaml"})
  {
    rviz_projector::CalibrationFile calibration;
    EXPECT_EQ("", rviz_projector::loadCalibrationFile(std::string(CONFIG_DIR) + "/" + name, calibration)) << name;
    EXPECT_TRUE(calibration.warnings.empty()) << name << ": " << calibration.warnings.front();
    // K and P agree (a projector has no rectification).
    EXPECT_EQ(calibration.info.K[0], calibration.info.P[0]) << name;
    EXPECT_EQ(calibration.info.K[2], calibration.info.P[2]) << name;
    EXPECT_EQ(calibration.info.K[4], calibration.info.P[5]) << name;
    EXPECT_EQ(calibration.info.K[5], calibration.info.P[6]) << name;
  }
}

TEST(CalibrationFile, TemplateIsACentredLensFromTheThrowRatio)
{
  rviz_projector::CalibrationFile calibration;
  ASSERT_EQ("", rviz_projector::loadCalibrationFile(std::string(CONFIG_DIR) + "/projector_template.yaml", calibration));
  const sensor_msgs::CameraInfo& info = calibration.info;
  EXPECT_DOUBLE_EQ((info.width - 1) / 2.0, info.P[2]);
  EXPECT_DOUBLE_EQ((info.height - 1) / 2.0, info.P[6]);
  EXPECT_DOUBLE_EQ(1.5 * info.width, info.P[0]);  // throw ratio 1.5
}

TEST(CalibrationFile, ResolvesPackageAndFileUrls)
{
  std::string path;
  EXPECT_EQ("", rviz_projector::resolveCalibrationUrl("package://rviz_projector/config/pa503w.yaml", path));
  EXPECT_EQ(std::string(CONFIG_DIR) + "/pa503w.yaml", path);
  EXPECT_EQ("", rviz_projector::resolveCalibrationUrl("file:///tmp/p.yaml", path));
  EXPECT_EQ("/tmp/p.yaml", path);
  EXPECT_NE("", rviz_projector::resolveCalibrationUrl("package://rviz_projector", path));
  EXPECT_NE("", rviz_projector::resolveCalibrationUrl("http://example.invalid/p.yaml", path));
}

TEST(CalibrationFile, WarnsWhenKAndPDisagree)
{
  // The reference set-up's mistake: cy = 817 in K, 750 in P.
  const std::string file = ::testing::TempDir() + "/k_p_disagree.yaml";
  FILE* out = std::fopen(file.c_str(), "w");
  ASSERT_TRUE(out != nullptr);
  std::fputs("image_width: 1280\nimage_height: 800\ncamera_matrix: {rows: 3, cols: 3, data: [1900, 0, 640, 0, 1900, "
             "817, 0, 0, 1]}\ndistortion_model: plumb_bob\ndistortion_coefficients: {rows: 1, cols: 5, data: [0, 0, "
             "0, 0, 0]}\nrectification_matrix: {rows: 3, cols: 3, data: [1, 0, 0, 0, 1, 0, 0, 0, 1]}\n"
             "projection_matrix: {rows: 3, cols: 4, data: [1900, 0, 640, 0, 0, 1900, 750, 0, 0, 0, 1, 0]}\n",
             out);
  std::fclose(out);
  rviz_projector::CalibrationFile calibration;
  EXPECT_EQ("", rviz_projector::loadCalibrationFile(file, calibration));
  ASSERT_EQ(1u, calibration.warnings.size());
  EXPECT_NE(std::string::npos, calibration.warnings[0].find("disagree")) << calibration.warnings[0];
  std::remove(file.c_str());
}

TEST(CalibrationFile, HugeMatrixSizeIsRefusedWithoutOverflow)
{
  // Regression: rows x cols of distortion_coefficients (any size allowed) was multiplied in long
  // long: 2^62 x 4 overflowed (undefined behaviour; UBSan reports it, and the wrapped product, 0,
  // matched the empty data list). The size must be refused with the numbers the user wrote.
  const std::string file = ::testing::TempDir() + "/huge_distortion.yaml";
  FILE* out = std::fopen(file.c_str(), "w");
  ASSERT_TRUE(out != nullptr);
  std::fputs("image_width: 1280\nimage_height: 800\ncamera_matrix: {rows: 3, cols: 3, data: [1900, 0, 640, 0, 1900, "
             "400, 0, 0, 1]}\ndistortion_model: plumb_bob\ndistortion_coefficients: {rows: 4611686018427387904, "
             "cols: 4, data: []}\nrectification_matrix: {rows: 3, cols: 3, data: [1, 0, 0, 0, 1, 0, 0, 0, 1]}\n"
             "projection_matrix: {rows: 3, cols: 4, data: [1900, 0, 640, 0, 0, 1900, 400, 0, 0, 0, 1, 0]}\n",
             out);
  std::fclose(out);
  rviz_projector::CalibrationFile calibration;
  const std::string error = rviz_projector::loadCalibrationFile(file, calibration);
  EXPECT_NE(std::string::npos,
            error.find(file + ": field 'distortion_coefficients': 'data' has 0 numbers, expected rows x cols = "
                              "4611686018427387904 x 4"))
      << error;
  // The largest sizes YAML can hold: no overflow either.
  out = std::fopen(file.c_str(), "w");
  ASSERT_TRUE(out != nullptr);
  std::fputs("image_width: 1280\nimage_height: 800\ncamera_matrix: {rows: 3, cols: 3, data: [1900, 0, 640, 0, 1900, "
             "400, 0, 0, 1]}\ndistortion_coefficients: {rows: 9223372036854775807, cols: 9223372036854775807, "
             "data: [0]}\nrectification_matrix: {rows: 3, cols: 3, data: [1, 0, 0, 0, 1, 0, 0, 0, 1]}\n"
             "projection_matrix: {rows: 3, cols: 4, data: [1900, 0, 640, 0, 0, 1900, 400, 0, 0, 0, 1, 0]}\n",
             out);
  std::fclose(out);
  const std::string error_max = rviz_projector::loadCalibrationFile(file, calibration);
  EXPECT_NE(std::string::npos, error_max.find("'data' has 1 numbers, expected rows x cols = 9223372036854775807 x "
                                              "9223372036854775807"))
      << error_max;
  std::remove(file.c_str());
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "projector_info_publisher_test", ros::init_options::AnonymousName);
  ros::NodeHandle nh;  // keeps the node alive for the whole run
  return RUN_ALL_TESTS();
}
