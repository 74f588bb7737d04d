// Properties and .rviz configs: clamped numbers, unknown enums, garbage files. Part of the bad-input matrix of issue 4 in a real rviz (robustness_fixtures.h);
// run by test/rviz/robustness_config.test.
#include "robustness_fixtures.h"

// ---- Properties and configs -----------------------------------------------------------------

class ConfigRobustness : public RobustnessTest
{
protected:
  template <typename T>
  T* loadOne(const char* file, const QString& class_id)
  {
    const std::string error = rviz_projector_test::loadRvizFile(rviz_->manager(), rviz_projector_test::configFile(file));
    EXPECT_EQ(error, "") << file;
    waitFor([&] { return !rviz_projector_test::displaysOfClass(rviz_->manager(), class_id).empty(); });
    const auto found = rviz_projector_test::displaysOfClass(rviz_->manager(), class_id);
    EXPECT_EQ(found.size(), 1u) << file;
    return found.empty() ? nullptr : dynamic_cast<T*>(found.front());
  }
  static double number(rviz::Display* d, const char* name) { return d->subProp(name)->getValue().toDouble(); }
};

TEST_F(ConfigRobustness, PathNumbersAreClampedOrFallBack)
{
  // path_bad_numbers.rviz: every numeric property negative, zero, NaN, huge or not a number.
  auto* d = loadOne<ProjectedPathDisplay>("path_bad_numbers.rviz", "rviz_projector/ProjectedPath");
  ASSERT_NE(d, nullptr);
  EXPECT_FLOAT_EQ(number(d, "Spacing"), 0.01f) << "-1 -> minimum";
  EXPECT_FLOAT_EQ(number(d, "Shaft length"), 0.005f) << "0 -> minimum";
  EXPECT_FLOAT_EQ(number(d, "Shaft diameter"), 0.005f) << "nan -> minimum";
  EXPECT_FLOAT_EQ(number(d, "Head length"), 10.0f) << "1e30 -> maximum";
  EXPECT_FLOAT_EQ(number(d, "Head diameter"), 0.005f) << "'abc' -> 0 -> minimum";
  EXPECT_FLOAT_EQ(number(d, "Destination circle diameter"), 10.0f) << "inf -> maximum";
  EXPECT_FLOAT_EQ(number(d, "Alpha"), 0.0f) << "-5 -> minimum";
  EXPECT_FLOAT_EQ(number(d, "Height above floor"), 10.0f) << "1e9 -> maximum";
  EXPECT_GE(d->subProp("Queue Size")->getValue().toInt(), 0) << "Queue Size -3";
  // Whatever was loaded, a path is drawn with finite arrows.
  ros::Publisher pub = nh_.advertise<nav_msgs::Path>(kPathTopic, 1, true);
  pub.publish(makePath("map", line(Vec3{0, 0, 0}, Vec3{30, 0, 0}, 300)));
  ASSERT_TRUE(waitFor([&] { return d->spacedPath().has_destination; }));
  for (const auto& a : d->spacedPath().arrows)
  {
    ASSERT_TRUE(rviz_projector::isFinite(a.tip) && rviz_projector::isFinite(a.tail));
  }
  EXPECT_FALSE(rviz_->renderMainView().isNull());
}

TEST_F(ConfigRobustness, PathUnknownEnumValuesFallBackToTheFirstOption)
{
  auto* d = loadOne<ProjectedPathDisplay>("path_bad_enums.rviz", "rviz_projector/ProjectedPath");
  ASSERT_NE(d, nullptr);
  ros::Publisher pub = nh_.advertise<nav_msgs::Path>(kPathTopic, 1, true);
  pub.publish(makePath("map", line(Vec3{0, 0, 0}, Vec3{3, 0, 0}, 31)));
  ASSERT_TRUE(waitFor([&] { return d->spacedPath().has_destination; }));
  // "Spacing mode: Diagonal" behaves as Exact, "Style: Neon" as Flat (3 triangles per arrow).
  EXPECT_EQ(d->spacedPath().arrows.size(), rviz_projector_test::defaultExactArrows(3.0));
  EXPECT_EQ(d->arrowTriangleCount(), 3u * d->spacedPath().arrows.size());
  EXPECT_EQ(statusOf(d, "Path").level, rviz::StatusProperty::Ok);
}

// Issue 4: "each loads with a clamped value or a fallback and a warning status". Unknown choices
// are replaced by the default (the panel shows it) and listed in the display's Config warning.
TEST_F(ConfigRobustness, PathUnknownEnumValuesGetAWarning)
{
  auto* d = loadOne<ProjectedPathDisplay>("path_bad_enums.rviz", "rviz_projector/ProjectedPath");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->subProp("Spacing mode")->getValue().toString().toStdString(), "Exact");
  EXPECT_EQ(d->subProp("Style")->getValue().toString().toStdString(), "Flat");
  const Status s = statusOf(d, "Config");
  EXPECT_EQ(s.level, rviz::StatusProperty::Warn);
  EXPECT_NE(s.text.indexOf("Spacing mode: 'Diagonal' -> Exact"), -1) << text(s);
  EXPECT_NE(s.text.indexOf("Style: 'Neon' -> Flat"), -1) << text(s);
}

// Numbers out of range in a config are clamped (rviz's FloatProperty does it in setValue()); the
// display compares the config's value with the property's and lists the changes.
TEST_F(ConfigRobustness, PathClampedNumbersGetAWarning)
{
  auto* d = loadOne<ProjectedPathDisplay>("path_bad_numbers.rviz", "rviz_projector/ProjectedPath");
  ASSERT_NE(d, nullptr);
  const Status s = statusOf(d, "Config");
  EXPECT_EQ(s.level, rviz::StatusProperty::Warn);
  for (const char* change : {"Spacing: '-1' -> 0.01", "Shaft length: '0' -> 0.005", "Shaft diameter: 'nan' -> 0.005",
                             "Head length: '1e30' -> 10", "Head diameter: 'abc' -> 0.005", "Alpha: '-5' -> 0"})
  {
    EXPECT_NE(s.text.indexOf(change), -1) << change << " not in: " << text(s);
  }
}

TEST_F(ConfigRobustness, CameraNumbersAreClampedAndTheScreenFallsBack)
{
  // camera_bad_values.rviz: near clip -1, far clip 0, frame rate 'abc', image rate -2,
  // output screen "HDMI-9" (does not exist), full screen "maybe".
  auto* d = loadOne<ProjectorCameraDisplay>("camera_bad_values.rviz", "rviz_projector/ProjectorCamera");
  ASSERT_NE(d, nullptr);
  EXPECT_FLOAT_EQ(number(d, "Near clip"), 0.001f);
  EXPECT_FLOAT_EQ(number(d, "Far clip"), 0.01f);
  EXPECT_EQ(d->subProp("Frame rate limit")->getValue().toInt(), 1);
  EXPECT_FLOAT_EQ(d->subProp("Image output")->subProp("Image rate")->getValue().toFloat(), 0.1f);
  static_tf_->sendTransform(rviz_projector_test::projectorMount("map", kOptical, 0.0, 0.0, 1.2, 0.9));
  ros::Publisher info = nh_.advertise<sensor_msgs::CameraInfo>(kInfoTopic, 1, true);
  info.publish(rviz_projector_test::cameraInfo(kOptical, 1280, 800, 1300, 639.5, 399.5));
  ASSERT_TRUE(waitFor([&] { return d->hasLens() && d->outputWindow() && d->outputWindow()->isVisible(); }));
  const Status output = statusOf(d, "Output");
  EXPECT_EQ(output.level, rviz::StatusProperty::Warn);
  EXPECT_TRUE(output.text.startsWith("Screen 'HDMI-9' is not connected")) << text(output);
  EXPECT_FALSE(grabProjector(d).isNull());
  EXPECT_FALSE(rviz_->renderMainView().isNull());
}

TEST_F(ConfigRobustness, CameraFarClipBeforeNearClipIsAWarning)
{
  auto* d = loadOne<ProjectorCameraDisplay>("camera_clip_inverted.rviz", "rviz_projector/ProjectorCamera");
  ASSERT_NE(d, nullptr);
  const Status s = statusOf(d, "Clipping");
  EXPECT_EQ(s.level, rviz::StatusProperty::Warn);
  EXPECT_EQ(text(s), "Far clip must be beyond near clip: using 50000 m");
}

// An unknown "Output screen" in a config is reported at load, even with the display disabled.
TEST_F(ConfigRobustness, CameraUnknownScreenIsReportedWhileDisabled)
{
  auto* d = loadOne<ProjectorCameraDisplay>("camera_disabled_unknown_screen.rviz", "rviz_projector/ProjectorCamera");
  ASSERT_NE(d, nullptr);
  ASSERT_FALSE(d->isEnabled());
  const Status s = statusOf(d, "Output");
  EXPECT_EQ(s.level, rviz::StatusProperty::Warn);
  EXPECT_TRUE(s.text.startsWith("Screen 'HDMI-9' is not connected")) << text(s);
}

TEST_F(ConfigRobustness, GarbageConfigFileIsRefusedByTheReader)
{
  // Not YAML at all: rviz's reader refuses it; nothing is loaded, nothing crashes.
  rviz::Config config;
  rviz::YamlConfigReader reader;
  reader.readFile(config, rviz_projector_test::configFile("not_yaml.rviz"));
  EXPECT_TRUE(reader.error());
  EXPECT_FALSE(rviz_->renderMainView().isNull());
}
