// projector_host's config check (src/host/host_config.cpp) and command line (host_options.cpp),
// with rviz's real display factory (pluginlib): the verdicts are compared with the contents of the
// files written here, by hand.
#include <fstream>
#include <string>

#include <QDir>
#include <QTemporaryDir>
#include <gtest/gtest.h>
#include <rviz/visualization_manager.h>

#include "../../src/host/host_config.h"
#include "../../src/host/host_options.h"
#include "../rviz/rviz_test_fixture.h"

namespace
{
using rviz_projector::checkHostConfig;
using rviz_projector::HostConfigCheck;
using rviz_projector::MissingPlugin;

const char* const kGood = R"(Visualization Manager:
  Class: ""
  Displays:
    - Class: rviz/Grid
      Enabled: true
      Name: Grid
      Value: true
    - Class: rviz/Group
      Enabled: true
      Name: Projection
      Displays:
        - Class: rviz_projector/ProjectedPath
          Enabled: true
          Name: Path
          Topic: /plan
          Arrow color: 255; 0; 255
          Path timeout: 3
          Value: true
        - Class: rviz_projector/ProjectorCamera
          Enabled: false
          Name: Projector
          Full screen: true
          Frame rate limit: 30
          Value: false
  Enabled: true
  Global Options:
    Fixed Frame: map
  Name: root
  Value: true
)";

class HostConfigTest : public rviz_projector_test::RvizTest
{
protected:
  QString write(const std::string& text)
  {
    const QString path = dir_.filePath(QString("config%1.rviz").arg(++files_));
    std::ofstream(path.toStdString()) << text;
    return path;
  }
  HostConfigCheck check(const std::string& text, MissingPlugin missing = MissingPlugin::Refuse)
  {
    return checkHostConfig(write(text), *rviz_->manager()->getDisplayFactory(), missing);
  }
  static std::string replaced(std::string text, const std::string& from, const std::string& to)
  {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? text : text.replace(at, from.size(), to);
  }

  QTemporaryDir dir_;
  int files_ = 0;
};

TEST_F(HostConfigTest, GoodConfigListsEveryDisplayIncludingGroups)
{
  const HostConfigCheck c = check(kGood);
  EXPECT_EQ(c.error, "");
  EXPECT_TRUE(c.warnings.empty());
  ASSERT_EQ(c.displays.size(), 4u);
  EXPECT_EQ(c.displays[0].class_id, "rviz/Grid");
  EXPECT_EQ(c.displays[1].class_id, "rviz/Group");
  EXPECT_EQ(c.displays[2].name, "Path");
  EXPECT_EQ(c.displays[3].class_id, "rviz_projector/ProjectorCamera");
  EXPECT_FALSE(c.displays[3].enabled);
  EXPECT_EQ(c.projectors, 1);
  EXPECT_EQ(c.manager_config.mapGetChild("Displays").listLength(), 2);
}

TEST_F(HostConfigTest, MissingFileBadYamlAndNotRvizAreRefused)
{
  EXPECT_NE(checkHostConfig(dir_.filePath("nowhere.rviz"), *rviz_->manager()->getDisplayFactory(), MissingPlugin::Warn)
                .error.find("does not exist"),
            std::string::npos);
  EXPECT_NE(check(std::string(kGood) + "  - [unclosed\n").error.find("not valid YAML"), std::string::npos);
  EXPECT_NE(check("Panels: []\n").error.find("no 'Visualization Manager'"), std::string::npos);
  EXPECT_NE(checkHostConfig(dir_.path(), *rviz_->manager()->getDisplayFactory(), MissingPlugin::Warn)
                .error.find("not a readable file"),
            std::string::npos);
}

TEST_F(HostConfigTest, NoProjectorCameraIsRefused)
{
  const HostConfigCheck c = check(replaced(kGood, "rviz_projector/ProjectorCamera", "rviz/Axes"));
  EXPECT_NE(c.error.find("no rviz_projector/ProjectorCamera"), std::string::npos) << c.error;
}

TEST_F(HostConfigTest, MissingPluginWarnsAtStartAndIsRefusedOnReload)
{
  const std::string text = replaced(kGood, "rviz/Grid", "no_such_pkg/NoSuchDisplay");
  const HostConfigCheck start = check(text, MissingPlugin::Warn);
  EXPECT_EQ(start.error, "");
  ASSERT_EQ(start.warnings.size(), 1u);
  EXPECT_NE(start.warnings[0].find("display 'Grid' (no_such_pkg/NoSuchDisplay): the plugin is not installed"),
            std::string::npos)
      << start.warnings[0];
  EXPECT_FALSE(start.displays[0].available);
  const HostConfigCheck reload = check(text, MissingPlugin::Refuse);
  EXPECT_NE(reload.error.find("not installed"), std::string::npos) << reload.error;
}

TEST_F(HostConfigTest, PropertyValuesOfTheWrongTypeAreRefusedWithTheirPath)
{
  struct Case
  {
    const char* from;
    const char* to;
    const char* expected;
  };
  const Case cases[] = {
      {"Frame rate limit: 30", "Frame rate limit: fast", "Frame rate limit: 'fast' is not a whole number"},
      {"Full screen: true", "Full screen: maybe", "Full screen: 'maybe' is not true or false"},
      {"Arrow color: 255; 0; 255", "Arrow color: 12; banana", "Arrow color: '12; banana' is not a colour"},
      {"Path timeout: 3", "Path timeout: soon", "Path timeout: 'soon' is not a number"},
  };
  for (const Case& c : cases)
  {
    const HostConfigCheck result = check(replaced(kGood, c.from, c.to));
    EXPECT_NE(result.error.find(c.expected), std::string::npos) << c.from << " -> " << result.error;
  }
  // Keys rviz does not know are ignored, as rviz ignores them (older configs).
  EXPECT_EQ(check(replaced(kGood, "Path timeout: 3", "Path timeout: 3\n          Old key: x")).error, "");
}

TEST(HostOptions, ParsesTheCommandLine)
{
  using rviz_projector::parseHostOptions;
  auto r = parseHostOptions({"a.rviz"});
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.options.config, "a.rviz");
  EXPECT_FALSE(r.options.watch);
  r = parseHostOptions({"--watch", "a.rviz"});
  EXPECT_TRUE(r.options.watch);
  r = parseHostOptions({"-w", "a.rviz"});
  EXPECT_TRUE(r.options.watch);
  EXPECT_FALSE(parseHostOptions({"a.rviz"}).options.all_displays);
  EXPECT_TRUE(parseHostOptions({"--all-displays", "a.rviz"}).options.all_displays);
  EXPECT_NE(rviz_projector::hostUsage().find("--all-displays"), std::string::npos);
  EXPECT_TRUE(parseHostOptions({"--help"}).help);
  EXPECT_EQ(parseHostOptions({}).error, "no config file given");
  EXPECT_EQ(parseHostOptions({"--fast", "a.rviz"}).error, "unknown option '--fast'");
  EXPECT_NE(parseHostOptions({"a.rviz", "b.rviz"}).error.find("more than one config"), std::string::npos);
  EXPECT_EQ(parseHostOptions({"a.rviz"}).options.keep_alive, 1.0);
  EXPECT_EQ(parseHostOptions({"--keep-alive", "0", "a.rviz"}).options.keep_alive, 0.0);
  EXPECT_EQ(parseHostOptions({"--keep-alive", "2.5", "a.rviz"}).options.keep_alive, 2.5);
  for (const char* bad : {"-1", "x", "1s", "nan", "inf"})
  {
    EXPECT_EQ(parseHostOptions({"--keep-alive", bad, "a.rviz"}).error, "--keep-alive needs a number of seconds >= 0")
        << bad;
  }
  EXPECT_NE(parseHostOptions({"a.rviz", "--keep-alive"}).error, "");
}
}  // namespace
