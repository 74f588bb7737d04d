// ProjectionChangeCounter: the contract its header states (monotonic, +1 per bump, process-wide,
// atomic; no reset), the only thing ProjectorCamera relies on to skip unchanged frames.
#include <gtest/gtest.h>

#include <cstdint>
#include <thread>
#include <vector>

#include "rviz_projector/displays/projection_change_counter.h"

using rviz_projector::ProjectionChangeCounter;

TEST(ProjectionChangeCounter, EachBumpAddsExactlyOne)
{
  const std::uint64_t before = ProjectionChangeCounter::value();
  EXPECT_EQ(ProjectionChangeCounter::value(), before) << "reading does not change the value";
  ProjectionChangeCounter::bump();
  EXPECT_EQ(ProjectionChangeCounter::value(), before + 1);
  for (int i = 0; i < 1000; ++i)
  {
    ProjectionChangeCounter::bump();
  }
  EXPECT_EQ(ProjectionChangeCounter::value(), before + 1001);
}

TEST(ProjectionChangeCounter, ReaderSeesAChangeIffSomethingBumped)
{
  // How ProjectorCamera uses it: keep the last value seen, compare for equality.
  std::uint64_t last_seen = ProjectionChangeCounter::value();
  EXPECT_EQ(ProjectionChangeCounter::value(), last_seen) << "nothing bumped: no render needed";
  ProjectionChangeCounter::bump();
  EXPECT_NE(ProjectionChangeCounter::value(), last_seen) << "a bump: render again";
  last_seen = ProjectionChangeCounter::value();
  EXPECT_EQ(ProjectionChangeCounter::value(), last_seen);
}

TEST(ProjectionChangeCounter, IsProcessWideAndNeverLosesABump)
{
  // Every thread (like every display and library) shares the one counter: bumps from several
  // threads at once all count, and a reader never sees the value go down.
  const std::uint64_t before = ProjectionChangeCounter::value();
  constexpr int kThreads = 4;
  constexpr int kBumps = 20000;
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
  {
    threads.emplace_back([] {
      for (int i = 0; i < kBumps; ++i)
      {
        ProjectionChangeCounter::bump();
      }
    });
  }
  std::uint64_t previous = before;
  bool monotonic = true;
  for (int i = 0; i < 100000; ++i)
  {
    const std::uint64_t now = ProjectionChangeCounter::value();
    monotonic = monotonic && now >= previous;
    previous = now;
  }
  for (std::thread& t : threads)
  {
    t.join();
  }
  EXPECT_TRUE(monotonic);
  EXPECT_EQ(ProjectionChangeCounter::value(), before + std::uint64_t(kThreads) * kBumps);
}
