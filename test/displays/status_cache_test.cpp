// StatusCache: which status calls ProjectorCamera forwards to rviz (only changes).
#include <gtest/gtest.h>

#include <QString>

#include "rviz_projector/displays/status_cache.h"

using rviz_projector::StatusCache;

namespace
{
constexpr int kOk = 0, kWarn = 1, kError = 2;  // rviz::StatusProperty's levels
}  // namespace

TEST(StatusCache, OnlyChangesAreForwarded)
{
  StatusCache cache;
  EXPECT_TRUE(cache.set(kOk, "Transform", "OK")) << "a new status is shown";
  EXPECT_FALSE(cache.set(kOk, "Transform", "OK")) << "the same again: nothing to show";
  EXPECT_TRUE(cache.set(kError, "Transform", "OK")) << "another level";
  EXPECT_TRUE(cache.set(kError, "Transform", "No transform")) << "another text";
  EXPECT_FALSE(cache.set(kError, "Transform", "No transform"));
  EXPECT_TRUE(cache.set(kError, "Output", "No transform")) << "another name is another status";
  EXPECT_EQ(cache.text("Transform"), "No transform");
  EXPECT_EQ(cache.text("Output"), "No transform");
}

TEST(StatusCache, RemoveSaysWhetherTheStatusWasShown)
{
  StatusCache cache;
  EXPECT_FALSE(cache.remove("Scaling")) << "never shown: nothing to delete";
  cache.set(kWarn, "Scaling", "letterboxed");
  EXPECT_TRUE(cache.has("Scaling"));
  EXPECT_TRUE(cache.remove("Scaling"));
  EXPECT_FALSE(cache.has("Scaling"));
  EXPECT_FALSE(cache.remove("Scaling")) << "already deleted";
  EXPECT_TRUE(cache.set(kWarn, "Scaling", "letterboxed")) << "shown again after its removal";
  EXPECT_TRUE(cache.text("Main view").isEmpty());
}

TEST(StatusCache, AfterClearEveryStatusIsShownAgain)
{
  // rviz's Reset clears the statuses: the display must raise the ones that still hold.
  StatusCache cache;
  cache.set(kOk, "Transform", "OK");
  cache.set(kError, "CameraInfo", "none");
  cache.clear();
  EXPECT_FALSE(cache.has("Transform"));
  EXPECT_TRUE(cache.set(kOk, "Transform", "OK"));
  EXPECT_TRUE(cache.set(kError, "CameraInfo", "none"));
}
