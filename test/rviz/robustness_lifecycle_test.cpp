// Lifecycle: add/remove cycles, topic and fixed-frame changes, reset, config reloads. Part of the bad-input matrix of issue 4 in a real rviz (robustness_fixtures.h);
// run by test/rviz/robustness_lifecycle.test.
#include <OgreRoot.h>
#include <OgreTextureManager.h>

#include "robustness_fixtures.h"

// ---- Lifecycle ------------------------------------------------------------------------------

class LifecycleRobustness : public CameraRobustness
{
protected:
  rviz_projector_test::OgreCounts counts() { return rviz_projector_test::ogreCounts(rviz_->manager()->getSceneManager()); }
};

TEST_F(LifecycleRobustness, HundredCyclesOfEachDisplayLeaveNothingBehind)
{
  // SetUp waited until the path is projected: every Ogre object of both displays exists.
  const auto before = counts();
  const int windows_before = projectorWindows(false);
  for (int i = 0; i < 100; ++i)
  {
    rviz::Display* path = rviz_->addDisplay("rviz_projector/ProjectedPath", "cycle path");
    path->subProp("Topic")->setValue(kPathTopic);  // the latched path arrives while it cycles
    rviz::Display* mask = rviz_->addDisplay("rviz_projector/ProjectionMask", "cycle mask");
    rviz::Display* camera = rviz_->addDisplay("rviz_projector/ProjectorCamera", "cycle projector");
    camera->subProp("Topic")->setValue(kInfoTopic);
    auto* projector = dynamic_cast<ProjectorCameraDisplay*>(camera);
    ASSERT_NE(projector, nullptr);
    ASSERT_NE(projector->visibilityBit(), 0u) << "cycle " << i << ": visibility bits leak";
    // The event loop runs between the steps (pacing of the cycles; they wait for nothing).
    spinFor(0.01);
    path->setEnabled(false);
    mask->setEnabled(false);
    camera->setEnabled(false);
    spinFor(0.005);
    path->setEnabled(true);
    mask->setEnabled(true);
    camera->setEnabled(true);
    spinFor(0.01);
    delete path;
    delete mask;
    delete camera;
    QApplication::processEvents();
  }
  waitFor([&] { return projectorWindows(false) == windows_before && counts() == before; });
  EXPECT_EQ(projectorWindows(false), windows_before) << "no stray windows";
  EXPECT_EQ(projectorWindows(true), 1);
  const auto after = counts();
  EXPECT_TRUE(after == before) << "before: " << before.describe() << "\nafter:  " << after.describe();
  // A projector added now gets a bit and renders (the visibility bits were all freed).
  auto* late = dynamic_cast<ProjectorCameraDisplay*>(rviz_->addDisplay("rviz_projector/ProjectorCamera", "late"));
  late->subProp("Topic")->setValue(kInfoTopic);
  EXPECT_NE(late->visibilityBit(), 0u);
  ASSERT_TRUE(waitFor([&] { return late->hasLens() && late->outputWindow() && late->outputWindow()->isVisible(); }));
  EXPECT_TRUE(waitFor([&] { return countColour(grabProjector(late), kMagenta) > 100; }));
  expectProjects("the first projector after the cycles");
}

TEST_F(LifecycleRobustness, CyclesOfADistortingProjectorLeaveNoTextureOrSceneBehind)
{
  // Issue 24: a projector whose lens has a D renders through a texture and a scene of its own
  // (DistortionWarp); both go with the display, and with a lens that changes back to no D.
  ros::Publisher distorted_pub = nh_.advertise<sensor_msgs::CameraInfo>("/robustness/distorted/camera_info", 1, true);
  sensor_msgs::CameraInfo distorted = good_;
  distorted.distortion_model = "plumb_bob";
  distorted.D = {-0.2, 0.05, 0.0, 0.0, 0.0};
  distorted_pub.publish(distorted);
  const auto textures = [] {
    std::size_t n = 0;
    for (auto it = Ogre::TextureManager::getSingleton().getResourceIterator(); it.hasMoreElements(); it.moveNext())
    {
      ++n;
    }
    return n;
  };
  const auto scenes = [] { return Ogre::Root::getSingleton().getSceneManagers().size(); };
  const auto before = counts();
  const std::size_t textures_before = textures(), scenes_before = scenes();
  for (int i = 0; i < 30; ++i)
  {
    auto* projector = dynamic_cast<ProjectorCameraDisplay*>(rviz_->addDisplay("rviz_projector/ProjectorCamera", "warped"));
    ASSERT_NE(projector, nullptr);
    projector->subProp("Topic")->setValue("/robustness/distorted/camera_info");
    ASSERT_TRUE(waitFor([&] {
      const Status s = statusOf(projector, "Distortion");
      return s.present && s.level == rviz::StatusProperty::Ok;
    })) << "cycle " << i << ": the warp never came up";
    EXPECT_EQ(textures(), textures_before + 1) << "cycle " << i << ": one texture for the ideal view";
    if (i % 2 == 1)
    {
      projector->subProp("Topic")->setValue(kInfoTopic);  // the same lens without D: the warp goes
      ASSERT_TRUE(waitFor([&] { return !statusOf(projector, "Distortion").present; })) << "cycle " << i;
      EXPECT_EQ(textures(), textures_before) << "cycle " << i << ": D zero keeps no texture";
    }
    spinFor(0.01);
    delete projector;
    QApplication::processEvents();
  }
  waitFor([&] { return counts() == before && textures() == textures_before; });
  EXPECT_EQ(textures(), textures_before);
  EXPECT_EQ(scenes(), scenes_before);
  const auto after = counts();
  EXPECT_TRUE(after == before) << "before: " << before.describe() << "\nafter:  " << after.describe();
  expectProjects("the first projector after the cycles");
}

TEST_F(LifecycleRobustness, TwoOfEachAtOnceAndRemovedInAnyOrder)
{
  rviz::Display* path2 = rviz_->addDisplay("rviz_projector/ProjectedPath", "Path 2");
  path2->subProp("Topic")->setValue("/robustness/plan2");
  ros::Publisher pub2 = nh_.advertise<nav_msgs::Path>("/robustness/plan2", 1, true);
  pub2.publish(makePath("map", line(Vec3{0.5, 0.4, 0}, Vec3{2.2, 0.4, 0}, 40)));
  auto* second = dynamic_cast<ProjectorCameraDisplay*>(rviz_->addDisplay("rviz_projector/ProjectorCamera", "Projector 2"));
  ASSERT_NE(second, nullptr);
  second->subProp("Topic")->setValue(kInfoTopic);
  ASSERT_TRUE(waitFor([&] { return second->hasLens() && projectorWindows(true) == 2; }));
  EXPECT_NE(second->visibilityBit(), projector_->visibilityBit());
  ASSERT_TRUE(waitFor([&] { return countColour(grabProjector(second), kMagenta) > 200; }));
  const int one_path = countColour(grabProjector(projector_), kMagenta);
  EXPECT_GT(one_path, 100);
  // Remove the FIRST projector and the first path: the others carry on.
  rviz::Display* path1 = rviz_projector_test::displaysOfClass(rviz_->manager(), "rviz_projector/ProjectedPath").front();
  delete projector_;
  projector_ = nullptr;
  delete path1;
  EXPECT_TRUE(waitFor([&] { return projectorWindows(true) == 1; }));
  EXPECT_TRUE(waitFor([&] { return countColour(grabProjector(second), kMagenta) > 100; })) << "path 2 in projector 2";
  delete second;
  delete path2;
  EXPECT_TRUE(waitFor([&] { return projectorWindows(false) == 0; }));
  EXPECT_FALSE(rviz_->renderMainView().isNull());
}

TEST_F(LifecycleRobustness, TopicChangesWhileMessagesFlow)
{
  auto* path = dynamic_cast<ProjectedPathDisplay*>(
      rviz_projector_test::displaysOfClass(rviz_->manager(), "rviz_projector/ProjectedPath").front());
  std::atomic<bool> stop{false};
  std::thread flow([&] {
    ros::Publisher a = nh_.advertise<nav_msgs::Path>("/robustness/flow_a", 5);
    ros::Publisher b = nh_.advertise<nav_msgs::Path>("/robustness/flow_b", 5);
    ros::Publisher ia = nh_.advertise<sensor_msgs::CameraInfo>("/robustness/info_a", 5);
    ros::Publisher ib = nh_.advertise<sensor_msgs::CameraInfo>("/robustness/info_b", 5);
    const auto info_a = rviz_projector_test::cameraInfo(kOptical, 1280, 800, 1300, 639.5, 399.5);
    const auto info_b = rviz_projector_test::cameraInfo(kOptical, 1024, 640, 1040, 511.5, 319.5);
    while (!stop)
    {
      a.publish(makePath("map", line(Vec3{0.5, 0, 0}, Vec3{2.2, 0, 0}, 40)));
      b.publish(makePath("map", line(Vec3{0.5, 0.3, 0}, Vec3{1.7, 0.3, 0}, 40)));
      ia.publish(info_a);
      ib.publish(info_b);
      // Pacing of the rate-controlled publisher (100 Hz), not a wait for anything.
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  });
  for (int i = 0; i < 30; ++i)
  {
    const bool even = i % 2 == 0;
    path->subProp("Topic")->setValue(even ? "/robustness/flow_a" : "/robustness/flow_b");
    projector_->subProp("Topic")->setValue(even ? "/robustness/info_a" : "/robustness/info_b");
    spinFor(0.05);  // pacing of the topic switches while messages flow, not a wait
  }
  // Last switch was to *_b: the display follows b.
  EXPECT_TRUE(waitFor([&] { return projector_->hasLens() && projector_->lens().width() == 1024; }));
  EXPECT_TRUE(waitFor([&] { return std::fabs(path->spacedPath().destination.x - 1.7) < 1e-9; }));
  stop = true;
  flow.join();
  EXPECT_EQ(statusOf(projector_, "CameraInfo").level, rviz::StatusProperty::Ok);
  EXPECT_EQ(statusOf(path, "Path").level, rviz::StatusProperty::Ok);
  EXPECT_EQ(projectorWindows(true), 1);
  expectProjects("after the topic changes");
}

TEST_F(LifecycleRobustness, FixedFrameChanges)
{
  auto* path = dynamic_cast<ProjectedPathDisplay*>(
      rviz_projector_test::displaysOfClass(rviz_->manager(), "rviz_projector/ProjectedPath").front());
  publishStaticTransform("map", "odom", 1.0, 0.0, 0.0, 0.0);
  rviz_->manager()->setFixedFrame("odom");
  // The path display redraws its last path in the new fixed frame.
  ASSERT_TRUE(waitFor([&] {
    return !path->spacedPath().arrows.empty() && std::fabs(path->spacedPath().destination.x - (2.2 - 1.0)) < 1e-9;
  }));
  EXPECT_NEAR(path->spacedPath().destination.x, 2.2 - 1.0, 1e-9) << "drawn in odom";
  expectProjects("fixed frame odom");
  // A fixed frame that does not exist: errors, background only, rviz renders.
  rviz_->manager()->setFixedFrame("no_such_fixed_frame");
  ASSERT_TRUE(waitFor([&] {
    projector_->renderNow();
    return statusOf(projector_, "Transform").text.indexOf("to fixed frame [no_such_fixed_frame]") != -1;
  })) << text(statusOf(projector_, "Transform"));
  EXPECT_EQ(statusOf(projector_, "Transform").level, rviz::StatusProperty::Error);
  expectBackgroundOnly("unknown fixed frame");
  path_pub_.publish(makePath("map", line(Vec3{0.5, 0, 0}, Vec3{2.2, 0, 0}, 40)));
  ASSERT_TRUE(waitFor([&] { return statusOf(path, "Transform").level == rviz::StatusProperty::Error; }))
      << text(statusOf(path, "Transform"));
  // Back to map: the path is drawn again from its next message.
  rviz_->manager()->setFixedFrame("map");
  path_pub_.publish(makePath("map", line(Vec3{0.5, 0, 0}, Vec3{2.2, 0, 0}, 40)));
  ASSERT_TRUE(waitFor([&] { return !path->spacedPath().arrows.empty(); }));
  expectProjects("fixed frame map again");
}

// A fixed-frame change redraws the last path in the new frame (rviz's MessageFilterDisplay would
// clear it until the planner publishes again; a latched plan never does).
TEST_F(LifecycleRobustness, PathSurvivesAFixedFrameChange)
{
  auto* path = dynamic_cast<ProjectedPathDisplay*>(
      rviz_projector_test::displaysOfClass(rviz_->manager(), "rviz_projector/ProjectedPath").front());
  ASSERT_TRUE(waitFor([&] { return !path->spacedPath().arrows.empty(); }));
  publishStaticTransform("map", "odom", 1.0, 0.0, 0.0, 0.0);
  rviz_->manager()->setFixedFrame("odom");
  EXPECT_TRUE(waitFor([&] { return !path->spacedPath().arrows.empty(); }, 3.0)) << text(statusOf(path, "Path"));
  EXPECT_NEAR(path->spacedPath().destination.x, 2.2 - 1.0, 1e-9) << "re-drawn in odom";
}

TEST_F(LifecycleRobustness, ResetKeepsRunningAndTheLatchedPathComesBack)
{
  auto* path = dynamic_cast<ProjectedPathDisplay*>(
      rviz_projector_test::displaysOfClass(rviz_->manager(), "rviz_projector/ProjectedPath").front());
  ASSERT_TRUE(waitFor([&] { return !path->spacedPath().arrows.empty(); }));
  rviz_->manager()->resetTime();  // what rviz's Reset button does: clears, then subscribes again
  // The latched path is delivered again, without a new publish.
  ASSERT_TRUE(waitFor([&] { return !path->spacedPath().arrows.empty(); })) << text(statusOf(path, "Path"));
  EXPECT_EQ(statusOf(path, "Path").level, rviz::StatusProperty::Ok);
  info_pub_.publish(good_);
  expectProjects("after Reset and a new CameraInfo");
  EXPECT_EQ(projectorWindows(true), 1);
}

// After rviz's Reset the ProjectorCamera subscribes again, so a LATCHED CameraInfo (how a
// projector's calibration is normally published, once) comes back by itself.
TEST_F(LifecycleRobustness, ResetGetsTheLatchedCameraInfoAgain)
{
  rviz_->manager()->resetTime();
  EXPECT_TRUE(waitFor([&] { return projector_->hasLens(); }, 3.0))
      << text(statusOf(projector_, "CameraInfo"));
  expectProjects("after Reset, with the latched CameraInfo only");
}

TEST_F(LifecycleRobustness, LoadingANewConfigWhileBothDisplaysAreActive)
{
  ASSERT_EQ(projectorWindows(true), 1);
  const std::string error =
      rviz_projector_test::loadRvizFile(rviz_->manager(), rviz_projector_test::configFile("two_projectors.rviz"));
  ASSERT_EQ(error, "");
  const auto projectors = rviz_projector_test::displaysOfClass(rviz_->manager(), "rviz_projector/ProjectorCamera");
  ASSERT_EQ(projectors.size(), 2u);
  ASSERT_TRUE(waitFor([&] { return projectorWindows(true) == 2; })) << "the old window is gone, two new ones";
  EXPECT_TRUE(waitFor([&] { return projectorWindows(false) == 2; })) << "no stray (hidden) windows";
  static_tf_->sendTransform(rviz_projector_test::projectorMount("map", kOptical, 0.0, 0.0, 1.2, 0.9));
  info_pub_.publish(good_);
  path_pub_.publish(makePath("map", line(Vec3{0.5, 0, 0}, Vec3{2.2, 0, 0}, 40)));
  for (rviz::Display* d : projectors)
  {
    auto* p = dynamic_cast<ProjectorCameraDisplay*>(d);
    EXPECT_NE(p->visibilityBit(), 0u);
    EXPECT_TRUE(waitFor([&] { return p->hasLens() && countColour(grabProjector(p), kMagenta) > 100; }))
        << d->getName().toStdString();
  }
  projector_ = nullptr;  // deleted by the load
  // And loading an empty config removes them all.
  ASSERT_EQ(rviz_projector_test::loadRvizFile(rviz_->manager(), rviz_projector_test::configFile("empty.rviz")), "");
  EXPECT_TRUE(waitFor([&] { return projectorWindows(false) == 0; }));
  EXPECT_FALSE(rviz_->renderMainView().isNull());
}
