// ProjectedPath: empty, huge, NaN/Inf, far-away and flooding paths. Part of the bad-input matrix of issue 4 in a real rviz (robustness_fixtures.h);
// run by test/rviz/robustness_path.test.
#include "robustness_fixtures.h"

TEST_F(PathRobustness, EmptyPath)
{
  ASSERT_TRUE(publishAndWait(makePath("odom", {})));
  EXPECT_EQ(path().level, rviz::StatusProperty::Warn);
  EXPECT_EQ(text(path()), "Empty path (no poses): nothing to draw");
  EXPECT_EQ(display_->arrowTriangleCount(), 0u);
  EXPECT_EQ(display_->circleTriangleCount(), 0u);
  expectRvizRenders();
}

TEST_F(PathRobustness, OnePoseTwoIdenticalAllIdentical)
{
  for (std::size_t n : {1u, 2u, 5000u})
  {
    ASSERT_TRUE(publishAndWait(makePath("odom", std::vector<Vec3>(n, Vec3{2.0, 1.0, 0.0})))) << n;
    EXPECT_EQ(path().level, rviz::StatusProperty::Ok) << n;
    EXPECT_EQ(text(path()), "0 arrows on 0.00 m of path") << n;
    EXPECT_EQ(display_->arrowTriangleCount(), 0u) << n;
    EXPECT_EQ(display_->circleTriangleCount(), 48u) << n << ": the destination circle alone";
    EXPECT_NEAR(display_->spacedPath().destination.x, 3.0, 1e-9);
    EXPECT_NEAR(display_->spacedPath().destination.y, 1.5, 1e-9);
  }
  expectRvizRenders();
}

TEST_F(PathRobustness, MillionPoses)
{
  // 10^6 poses, 1 mm apart: 1000 m of path.
  const auto points = line(Vec3{0, 0, 0}, Vec3{999.999, 0, 0}, 1000000);
  const auto start = std::chrono::steady_clock::now();
  ASSERT_TRUE(publishAndWait(makePath("odom", points), 60.0));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::size_t arrows = rviz_projector_test::defaultExactArrows(999.999);
  EXPECT_EQ(display_->spacedPath().arrows.size(), arrows);
  EXPECT_EQ(path().level, rviz::StatusProperty::Ok);
  EXPECT_EQ(text(path()), std::to_string(arrows) + " arrows on 1000.00 m of path");
  std::printf("10^6 poses: %zu arrows, %.2f s from publish to drawn\n", arrows, seconds);
  expectRvizRenders();
}

TEST_F(PathRobustness, ThreeDStyleOfAVeryLongPathIsCappedFlatIsNot)
{
  // 105 m at the smallest spacing: about 10,500 arrows, more than 3D builds (240 vertices each).
  display_->subProp("Spacing")->setValue(0.01);
  display_->subProp("Style")->setValue("3D");
  ASSERT_TRUE(publishAndWait(makePath("odom", line(Vec3{0, 0, 0}, Vec3{105, 0, 0}, 10501)), 30.0));
  const std::size_t arrows = display_->spacedPath().arrows.size();
  ASSERT_GT(arrows, rviz_projector::PathTriangles::kMaxSolidArrows);
  EXPECT_EQ(display_->arrowTriangleCount(),
            rviz_projector::PathTriangles::kMaxSolidArrows * rviz_projector::ArrowSolid::kVerticesPerArrow / 3);
  const Status style = statusOf(display_, "Style");
  ASSERT_TRUE(style.present);
  EXPECT_EQ(style.level, rviz::StatusProperty::Warn);
  EXPECT_NE(text(style).find(std::to_string(arrows - rviz_projector::PathTriangles::kMaxSolidArrows) + " left out"),
            std::string::npos)
      << text(style);
  EXPECT_EQ(path().level, rviz::StatusProperty::Ok);

  display_->subProp("Style")->setValue("Flat");
  EXPECT_FALSE(statusOf(display_, "Style").present);
  EXPECT_EQ(display_->arrowTriangleCount(), arrows * rviz_projector::ArrowOutline::kVerticesPerArrow / 3);
  expectRvizRenders();
}

TEST_F(PathRobustness, NanAndInfInSomePoses)
{
  auto points = line(Vec3{0, 0, 0}, Vec3{3, 0, 0}, 31);
  nav_msgs::Path p = makePath("odom", points);
  p.poses[2].pose.position.x = kNan;
  p.poses[5].pose.position.y = kInf;
  p.poses[9].pose.position.z = -kInf;
  p.poses[12].pose.orientation.w = kNan;
  p.poses[30].pose.orientation.x = kInf;  // the destination itself: the previous pose becomes it
  ASSERT_TRUE(publishAndWait(p));
  const std::size_t arrows = rviz_projector_test::defaultExactArrows(2.9);
  EXPECT_EQ(path().level, rviz::StatusProperty::Warn);
  EXPECT_EQ(text(path()), "5 poses with NaN/Inf or out-of-range values dropped; " + std::to_string(arrows) + " arrows drawn");
  EXPECT_EQ(display_->spacedPath().arrows.size(), arrows);
  EXPECT_NEAR(display_->spacedPath().destination.x, 1.0 + 2.9, 1e-9);
  for (const auto& a : display_->spacedPath().arrows)
  {
    ASSERT_TRUE(rviz_projector::isFinite(a.tip) && rviz_projector::isFinite(a.tail));
  }
  expectRvizRenders();
}

TEST_F(PathRobustness, NanOrInfInAllPoses)
{
  struct Case
  {
    const char* what;
    std::function<void(geometry_msgs::Pose&)> spoil;
  };
  const Case cases[] = {
      {"x NaN", [](geometry_msgs::Pose& p) { p.position.x = kNan; }},
      {"y Inf", [](geometry_msgs::Pose& p) { p.position.y = kInf; }},
      {"z -Inf", [](geometry_msgs::Pose& p) { p.position.z = -kInf; }},
      {"orientation NaN", [](geometry_msgs::Pose& p) { p.orientation.z = kNan; }},
  };
  for (const Case& c : cases)
  {
    // A good path first, so that the bad one has something to clear.
    ASSERT_TRUE(publishAndWait(makePath("odom", line(Vec3{0, 0, 0}, Vec3{2, 0, 0}, 21))));
    ASSERT_GT(display_->arrowTriangleCount(), 0u);
    nav_msgs::Path p = makePath("odom", line(Vec3{0, 0, 0}, Vec3{2, 0, 0}, 21));
    for (auto& pose : p.poses)
    {
      c.spoil(pose.pose);
    }
    ASSERT_TRUE(publishAndWait(p)) << c.what;
    EXPECT_EQ(path().level, rviz::StatusProperty::Warn) << c.what;
    EXPECT_EQ(text(path()), "All 21 poses have NaN/Inf or out-of-range values: nothing to draw") << c.what;
    EXPECT_EQ(display_->arrowTriangleCount(), 0u) << c.what;
    EXPECT_EQ(display_->circleTriangleCount(), 0u) << c.what;
  }
  expectRvizRenders();
}

TEST_F(PathRobustness, ZeroAndNonNormalisedQuaternionsAreIgnored)
{
  // Only positions matter for the arrows: orientations of any length, even zero, change nothing.
  const auto points = line(Vec3{0, 0, 0}, Vec3{3, 0, 0}, 31);
  ASSERT_TRUE(publishAndWait(makePath("odom", points, 0, 0, 0, 0)));
  EXPECT_EQ(path().level, rviz::StatusProperty::Ok);
  EXPECT_EQ(text(path()), std::to_string(rviz_projector_test::defaultExactArrows(3.0)) + " arrows on 3.00 m of path");
  const auto zero = display_->spacedPath().arrows;
  ASSERT_TRUE(publishAndWait(makePath("odom", points, 0, 0, 7, 7)));
  const auto scaled = display_->spacedPath().arrows;
  ASSERT_EQ(zero.size(), scaled.size());
  for (std::size_t k = 0; k < zero.size(); ++k)
  {
    EXPECT_EQ(zero[k].tip.x, scaled[k].tip.x);
    EXPECT_EQ(zero[k].tail.y, scaled[k].tail.y);
  }
}

TEST_F(PathRobustness, BillionMetreCoordinates)
{
  // 3 m of path a million kilometres away: same arrows as at the origin, finite.
  ASSERT_TRUE(publishAndWait(makePath("odom", line(Vec3{1e9, 1e9, 0}, Vec3{1e9 + 3, 1e9, 0}, 31))));
  EXPECT_EQ(path().level, rviz::StatusProperty::Ok);
  EXPECT_EQ(display_->spacedPath().arrows.size(), rviz_projector_test::defaultExactArrows(3.0));
  // A path 1e9 m long at the smallest spacing: bounded by max_arrows, with a warning.
  display_->subProp("Spacing")->setValue(0.01);
  ASSERT_TRUE(publishAndWait(makePath("odom", {Vec3{-5e8, 0, 0}, Vec3{5e8, 0, 0}})));
  EXPECT_EQ(path().level, rviz::StatusProperty::Warn);
  EXPECT_EQ(text(path()), "Path too long for the spacing: only the 100000 arrows nearest the destination are drawn");
  EXPECT_EQ(display_->spacedPath().arrows.size(), 100000u);
  expectRvizRenders();
}

TEST_F(PathRobustness, EmptyFrameIdIsAnError)
{
  nav_msgs::Path p = makePath("", line(Vec3{0, 0, 0}, Vec3{3, 0, 0}, 31));
  publisher_.publish(p);
  ASSERT_TRUE(waitFor([&] {
    const Status s = statusOf(display_, "Transform");
    return s.present && s.level == rviz::StatusProperty::Error;
  })) << text(statusOf(display_, "Transform"));
  EXPECT_EQ(text(statusOf(display_, "Transform")), "Path has an empty frame_id: nothing is drawn");
  EXPECT_EQ(display_->spacedPath().arrows.size(), 0u);
  expectRvizRenders();
}

TEST_F(PathRobustness, FrameAppearingLaterRecoversByItself)
{
  nav_msgs::Path p = makePath("late_odom", line(Vec3{0, 0, 0}, Vec3{3, 0, 0}, 31));
  p.header.stamp = ros::Time::now();
  publisher_.publish(p);
  // First a warning while the path waits for its tf (a path a moment ahead of its tf is normal),
  // an error once it has waited a second.
  ASSERT_TRUE(waitFor([&] {
    const Status s = statusOf(display_, "Transform");
    return s.present && s.level == rviz::StatusProperty::Warn &&
           s.text.startsWith("Waiting for the transform (an error after 1 s): ");
  })) << text(statusOf(display_, "Transform"));
  ASSERT_TRUE(waitFor([&] {
    const Status s = statusOf(display_, "Transform");
    return s.present && s.level == rviz::StatusProperty::Error;
  }));
  EXPECT_NE(statusOf(display_, "Transform").text.indexOf("late_odom"), -1) << text(statusOf(display_, "Transform"));
  EXPECT_EQ(display_->spacedPath().arrows.size(), 0u);
  EXPECT_FALSE(waitFor([&] { return !display_->spacedPath().arrows.empty(); }, 0.5))
      << "nothing is drawn while the frame is missing";
  // The transform shows up; the path is NOT published again.
  publishStaticTransform("map", "late_odom", 0.0, 0.0, 0.0, 0.0);
  ASSERT_TRUE(waitFor([&] { return display_->spacedPath().arrows.size() == rviz_projector_test::defaultExactArrows(3.0); },
                      10.0))
      << text(statusOf(display_, "Transform"));
  EXPECT_EQ(statusOf(display_, "Transform").level, rviz::StatusProperty::Ok);
  EXPECT_EQ(path().level, rviz::StatusProperty::Ok);
}

TEST_F(PathRobustness, FloodOf200PathsPerSecondKeepsLatencyFlat)
{
  // A publisher thread sends 200 paths/s for 10 s; each path's destination x encodes its number.
  // The display must keep up with the newest (not work through a growing backlog).
  constexpr int kRate = 200;
  constexpr double kSeconds = 10.0;
  std::atomic<int> sent{0};
  std::atomic<bool> stop{false};
  std::atomic<double> flood_start{-1.0};  // seconds after t0 when the first path was sent
  std::vector<double> sent_at(static_cast<std::size_t>(kRate * kSeconds) + 10, 0.0);
  const auto t0 = std::chrono::steady_clock::now();
  auto now = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  const std::size_t rss_before = rviz_projector_test::residentBytes();
  std::thread publisher([&] {
    ros::Publisher pub = nh_.advertise<nav_msgs::Path>(kPathTopic, 10);
    // Wait (bounded) until the display has connected to this publisher.
    while (pub.getNumSubscribers() == 0 && !stop && now() < 10.0)
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    const double start = now();
    flood_start = start;
    const int total = static_cast<int>(kRate * kSeconds);
    for (int i = 0; i < total && !stop; ++i)
    {
      auto p = boost::make_shared<nav_msgs::Path>(
          makePath("odom", line(Vec3{0, 0, 0}, Vec3{3.0 + 0.001 * i, 0, 0}, 300)));
      sent_at[static_cast<std::size_t>(i)] = now();
      pub.publish(p);
      sent = i + 1;
      // Pacing of the rate-controlled publisher (kRate paths/s), not a wait for anything.
      std::this_thread::sleep_until(t0 + std::chrono::duration<double>(start + (i + 1.0) / kRate));
    }
  });
  // Latency samples: when the display shows path i, how long ago was i sent?
  std::vector<std::pair<double, double>> samples;  // (time, latency)
  int last_seen = -1;
  while (sent < static_cast<int>(kRate * kSeconds) && now() < kSeconds + 15.0)
  {
    spinFor(0.01);
    if (!display_->spacedPath().has_destination)
    {
      continue;
    }
    const int i = static_cast<int>(std::lround((display_->spacedPath().destination.x - 1.0 - 3.0) / 0.001));
    if (i != last_seen && i >= 0 && i < sent)
    {
      last_seen = i;
      samples.emplace_back(now(), now() - sent_at[static_cast<std::size_t>(i)]);
    }
  }
  stop = true;
  publisher.join();
  ASSERT_TRUE(waitFor([&] {
    return std::lround((display_->spacedPath().destination.x - 4.0) / 0.001) == sent - 1;
  }, 3.0)) << "the newest path is shown in the end";
  ASSERT_GT(samples.size(), 20u) << "the display keeps showing new paths during the flood";
  // Mean latency over the first and the last second of the flood.
  auto mean = [&](double from, double to) {
    double sum = 0;
    int n = 0;
    for (const auto& s : samples)
    {
      if (s.first >= from && s.first < to)
      {
        sum += s.second;
        ++n;
      }
    }
    return n ? sum / n : 0.0;
  };
  ASSERT_GE(flood_start.load(), 0.0) << "the display never connected to the flood's publisher";
  const double early = mean(flood_start + 0.0, flood_start + 1.0);
  const double late = mean(flood_start + kSeconds - 1.0, flood_start + kSeconds);
  std::printf("flood: %d paths sent, %zu distinct shown, latency first second %.1f ms, last second %.1f ms\n",
              sent.load(), samples.size(), 1e3 * early, 1e3 * late);
  EXPECT_LT(late, std::max(0.25, 3.0 * early)) << "latency grows: a backlog builds up";
  if (!rviz_projector_test::underAddressSanitizer())
  {
    const double grown = (double(rviz_projector_test::residentBytes()) - double(rss_before)) / 1e6;
    std::printf("flood: resident memory grew by %.1f MB\n", grown);
    EXPECT_LT(grown, 100.0);
  }
  EXPECT_EQ(path().level, rviz::StatusProperty::Ok);
  expectRvizRenders();
}
