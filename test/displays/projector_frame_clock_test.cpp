// ProjectorFrameClock: ticks at the paced deadlines, an early tick only when the Frame rate limit
// allows it, none after stop(). Times are checked with wide margins (a loaded CI machine); the
// pacing arithmetic itself is FramePacer's (test/core/frame_pacer_test.cpp).
#include <gtest/gtest.h>

#include <QCoreApplication>
#include <QElapsedTimer>
#include <QThread>

#include "rviz_projector/displays/projector_frame_clock.h"

using rviz_projector::ProjectorFrameClock;

namespace
{
/// Delivers Qt events until `done` or `timeout` seconds; returns done().
template <typename Done>
bool waitFor(Done done, double timeout)
{
  QElapsedTimer clock;
  clock.start();
  while (!done() && clock.nsecsElapsed() < static_cast<qint64>(timeout * 1e9))
  {
    QCoreApplication::processEvents(QEventLoop::AllEvents, 5);
    QThread::usleep(200);
  }
  return done();
}

class FrameClockTest : public ::testing::Test
{
protected:
  static void SetUpTestSuite()
  {
    if (!QCoreApplication::instance())
    {
      static int argc = 1;
      static char name[] = "test_display_parts";
      static char* argv[] = { name, nullptr };
      app_ = new QCoreApplication(argc, argv);
    }
  }
  static QCoreApplication* app_;
};
QCoreApplication* FrameClockTest::app_ = nullptr;
}  // namespace

TEST_F(FrameClockTest, TicksAtOnceThenAtTheLimit)
{
  ProjectorFrameClock clock;
  clock.setRate(20.0, 0.0);  // 50 ms
  EXPECT_NEAR(clock.period(), 0.05, 1e-12);
  int ticks = 0;
  std::uint64_t frames = 0;
  QObject::connect(&clock, &ProjectorFrameClock::tick, [&] {
    ++ticks;
    clock.frameDone(++frames, true);  // every tick renders
  });
  QElapsedTimer elapsed;
  elapsed.start();
  clock.start();
  ASSERT_TRUE(waitFor([&] { return ticks >= 1; }, 2.0));
  EXPECT_LT(elapsed.elapsed(), 1000) << "the first tick comes at once";
  ASSERT_TRUE(waitFor([&] { return ticks >= 11; }, 5.0));
  // Ten periods after the first tick: at least 0.5 s (deadlines are never early).
  EXPECT_GE(elapsed.elapsed(), 450);
  EXPECT_TRUE(clock.isWaiting());
  EXPECT_GT(clock.frameRate(), 0.0);
  EXPECT_GE(clock.sinceLastFrame(), 0.0);
  clock.stop();
  const int stopped_at = ticks;
  EXPECT_FALSE(waitFor([&] { return ticks > stopped_at; }, 0.3)) << "ticked after stop()";
}

TEST_F(FrameClockTest, ScreenRefreshBelowTheLimitWins)
{
  ProjectorFrameClock clock;
  clock.setRate(60.0, 30.0);
  EXPECT_NEAR(clock.period(), 1.0 / 30.0, 1e-12);
  clock.setRate(60.0, 0.0);  // refresh unknown: the limit
  EXPECT_NEAR(clock.period(), 1.0 / 60.0, 1e-12);
}

TEST_F(FrameClockTest, EarlyFrameOnlyWhenALimitPeriodHasPassed)
{
  ProjectorFrameClock clock;
  clock.setRate(1.0, 0.0);  // deadlines 1 s apart: an early tick is easy to tell
  int ticks = 0;
  std::uint64_t frames = 0;
  QObject::connect(&clock, &ProjectorFrameClock::tick, [&] {
    ++ticks;
    clock.frameDone(++frames, true);
  });
  EXPECT_FALSE(clock.requestEarlyFrame()) << "not started: nothing to bring forward";
  clock.start();
  ASSERT_TRUE(waitFor([&] { return ticks == 1; }, 2.0));
  ASSERT_TRUE(clock.isWaiting());
  EXPECT_FALSE(clock.requestEarlyFrame()) << "a frame went out less than a period ago";
  // Just after the second deadline's frame, wait out most of a period and ask again.
  ASSERT_TRUE(waitFor([&] { return ticks == 2; }, 3.0));
  EXPECT_FALSE(clock.requestEarlyFrame());
  QElapsedTimer elapsed;
  elapsed.start();
  // With no frame rendered at a tick (nothing changed), the last frame ages past a period.
  QObject::disconnect(&clock, &ProjectorFrameClock::tick, nullptr, nullptr);
  QObject::connect(&clock, &ProjectorFrameClock::tick, [&] {
    ++ticks;
    clock.frameDone(frames, true);  // skipped: nothing changed
  });
  ASSERT_TRUE(waitFor([&] { return clock.sinceLastFrame() >= clock.period() + 0.05; }, 5.0));
  ASSERT_TRUE(clock.isWaiting());
  const int before = ticks;
  elapsed.restart();
  EXPECT_TRUE(clock.requestEarlyFrame());
  ASSERT_TRUE(waitFor([&] { return ticks > before; }, 2.0));
  EXPECT_LT(elapsed.elapsed(), 500) << "the early tick comes at once, not at the next deadline";
  clock.stop();
}
