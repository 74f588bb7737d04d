// chooseScreen: which screen the projector's output window goes to (hand-written expectations).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rviz_projector/core/screen_choice.h"

using rviz_projector::chooseScreen;
using rviz_projector::ScreenChoice;
using rviz_projector::ScreenInfo;

namespace
{
ScreenInfo screen(const std::string& name, int x, bool same_x_screen = true)
{
  ScreenInfo s;
  s.name = name;
  s.x = x;
  s.width = 1920;
  s.height = 1080;
  s.same_x_screen = same_x_screen;
  return s;
}

/// rviz on the laptop panel (index 0), two projectors on HDMI-1 and DP-1, all one X screen.
const std::vector<ScreenInfo> kThreeScreens = {screen("eDP-1", 0), screen("HDMI-1", 1920), screen("DP-1", 3840)};
}  // namespace

TEST(ScreenChoice, NoScreen)
{
  for (const std::string wanted : {"Automatic", "HDMI-1"})
  {
    const ScreenChoice c = chooseScreen({}, -1, wanted, {});
    EXPECT_EQ(c.index, -1);
    EXPECT_EQ(c.problem, "No screen is connected");
    EXPECT_FALSE(c.shares_rviz_screen);
  }
}

TEST(ScreenChoice, NamedScreenThatIsConnected)
{
  ScreenChoice c = chooseScreen(kThreeScreens, 0, "DP-1", {});
  EXPECT_EQ(c.index, 2);
  EXPECT_EQ(c.problem, "");
  EXPECT_FALSE(c.shares_rviz_screen);
  // Taken by another projector: still the one asked for (the user said so), no problem.
  c = chooseScreen(kThreeScreens, 0, "DP-1", {"DP-1"});
  EXPECT_EQ(c.index, 2);
  EXPECT_EQ(c.problem, "");
  // rviz's own screen, named: that one, flagged as shared with rviz.
  c = chooseScreen(kThreeScreens, 0, "eDP-1", {});
  EXPECT_EQ(c.index, 0);
  EXPECT_EQ(c.problem, "");
  EXPECT_TRUE(c.shares_rviz_screen);
  // A screen of another X screen, named explicitly: the user's choice is kept.
  c = chooseScreen({screen("eDP-1", 0), screen("HDMI-1", 0, false)}, 0, "HDMI-1", {});
  EXPECT_EQ(c.index, 1);
  EXPECT_EQ(c.problem, "");
}

TEST(ScreenChoice, NamedScreenThatIsMissingFallsBackToAutomatic)
{
  ScreenChoice c = chooseScreen(kThreeScreens, 0, "VGA-1", {});
  EXPECT_EQ(c.index, 1);  // the automatic choice: first screen that is not rviz's
  EXPECT_EQ(c.problem, "Screen 'VGA-1' is not connected");
  EXPECT_FALSE(c.shares_rviz_screen);
  // With HDMI-1 taken, the automatic choice moves on to DP-1.
  c = chooseScreen(kThreeScreens, 0, "VGA-1", {"HDMI-1"});
  EXPECT_EQ(c.index, 2);
  EXPECT_EQ(c.problem, "Screen 'VGA-1' is not connected");
  // Only rviz's screen left: rviz's, flagged.
  c = chooseScreen({screen("eDP-1", 0)}, 0, "VGA-1", {});
  EXPECT_EQ(c.index, 0);
  EXPECT_EQ(c.problem, "Screen 'VGA-1' is not connected");
  EXPECT_TRUE(c.shares_rviz_screen);
}

TEST(ScreenChoice, AutomaticTakesTheFirstFreeScreenThatIsNotRvizs)
{
  ScreenChoice c = chooseScreen(kThreeScreens, 0, "Automatic", {});
  EXPECT_EQ(c.index, 1);
  EXPECT_EQ(c.problem, "");
  EXPECT_FALSE(c.shares_rviz_screen);
  // rviz on the middle screen: the first other one is index 0.
  c = chooseScreen(kThreeScreens, 1, "Automatic", {});
  EXPECT_EQ(c.index, 0);
  EXPECT_EQ(c.problem, "");
  // An empty name means Automatic too.
  c = chooseScreen(kThreeScreens, 0, "", {});
  EXPECT_EQ(c.index, 1);
  EXPECT_EQ(c.problem, "");
}

TEST(ScreenChoice, TwoProjectorsOnAutomaticDoNotStack)
{
  // The first projector took HDMI-1: the second gets DP-1.
  ScreenChoice c = chooseScreen(kThreeScreens, 0, "Automatic", {"HDMI-1"});
  EXPECT_EQ(c.index, 2);
  EXPECT_EQ(c.problem, "");
  // Names taken that are not connected change nothing.
  c = chooseScreen(kThreeScreens, 0, "Automatic", {"VGA-7"});
  EXPECT_EQ(c.index, 1);
  // Both taken: the first non-rviz screen, shared, with a warning naming the screen.
  c = chooseScreen(kThreeScreens, 0, "Automatic", {"DP-1", "HDMI-1"});
  EXPECT_EQ(c.index, 1);
  EXPECT_NE(c.problem.find("HDMI-1"), std::string::npos) << c.problem;
  EXPECT_NE(c.problem.find("shar"), std::string::npos) << c.problem;
  EXPECT_NE(c.problem.find("another projector"), std::string::npos) << c.problem;
  EXPECT_FALSE(c.shares_rviz_screen);
}

TEST(ScreenChoice, AutomaticOnlyPicksScreensOfRvizsXScreen)
{
  // :0.0 holds rviz's panel, :0.1 (another X screen) a projector: Qt lists both, but a window of
  // rviz's X screen cannot go to the other one.
  const std::vector<ScreenInfo> screens = {screen("eDP-1", 0), screen(":0.1 HDMI-1", 0, false),
                                           screen("DP-1", 1920)};
  ScreenChoice c = chooseScreen(screens, 0, "Automatic", {});
  EXPECT_EQ(c.index, 2);
  EXPECT_EQ(c.problem, "");
  // Only the foreign X screen besides rviz's: rviz's own screen, flagged (no problem sentence).
  c = chooseScreen({screen("eDP-1", 0), screen("HDMI-1", 0, false)}, 0, "Automatic", {});
  EXPECT_EQ(c.index, 0);
  EXPECT_EQ(c.problem, "");
  EXPECT_TRUE(c.shares_rviz_screen);
  // rviz listed after the foreign screen: still rviz's.
  c = chooseScreen({screen("HDMI-1", 0, false), screen("eDP-1", 0)}, 1, "Automatic", {});
  EXPECT_EQ(c.index, 1);
  EXPECT_TRUE(c.shares_rviz_screen);
}

TEST(ScreenChoice, OnlyRvizsScreen)
{
  const ScreenChoice c = chooseScreen({screen("eDP-1", 0)}, 0, "Automatic", {});
  EXPECT_EQ(c.index, 0);
  EXPECT_EQ(c.problem, "");
  EXPECT_TRUE(c.shares_rviz_screen);
  // Even if another projector already shares it.
  const ScreenChoice again = chooseScreen({screen("eDP-1", 0)}, 0, "Automatic", {"eDP-1"});
  EXPECT_EQ(again.index, 0);
  EXPECT_TRUE(again.shares_rviz_screen);
}

TEST(ScreenChoice, UnknownRvizScreen)
{
  // rviz's screen unknown (-1, or an index that is not in the list): every sibling is a candidate.
  ScreenChoice c = chooseScreen(kThreeScreens, -1, "Automatic", {});
  EXPECT_EQ(c.index, 0);
  EXPECT_EQ(c.problem, "");
  EXPECT_FALSE(c.shares_rviz_screen);
  c = chooseScreen(kThreeScreens, 7, "Automatic", {"eDP-1"});
  EXPECT_EQ(c.index, 1);
  EXPECT_FALSE(c.shares_rviz_screen);
  // Nothing marked as rviz's sibling and rviz's screen unknown: the first screen, with a warning.
  c = chooseScreen({screen("A", 0, false), screen("B", 0, false)}, -1, "Automatic", {});
  EXPECT_EQ(c.index, 0);
  EXPECT_FALSE(c.problem.empty());
}
