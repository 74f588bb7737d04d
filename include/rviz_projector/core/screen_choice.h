// Which screen the projector's output window goes to: a pure function over plain screen
// descriptions (the display turns QScreens into ScreenInfo), testable without an X server.
#pragma once

#include <string>
#include <vector>

namespace rviz_projector
{
/// One connected screen, as the display sees it (Qt's QScreen, reduced to plain values).
struct ScreenInfo
{
  std::string name;  ///< QScreen::name(), e.g. "HDMI-1": what the display stores and shows
  int x = 0, y = 0, width = 0, height = 0;  ///< geometry in the virtual desktop, pixels
  bool same_x_screen = true;  ///< a virtual sibling of rviz's screen (QScreen::virtualSiblings())
};

struct ScreenChoice
{
  int index = -1;  ///< into the screens given to chooseScreen; -1: none
  std::string problem;  ///< empty: as asked; else a warning sentence for the user
  bool shares_rviz_screen = false;  ///< the chosen screen is the one rviz's main window is on
};

/// Name that asks chooseScreen for the automatic choice.
constexpr const char* kAutomaticScreen = "Automatic";

/**
 * wanted: a screen name or "Automatic" (an empty name too). rviz_screen: index of rviz's screen (-1 unknown). taken:
 * names of screens other projector windows already use.
 *
 * - No screens: index -1, problem "No screen is connected".
 * - A named screen that is connected: that one, even if another projector uses it
 *   (shares_rviz_screen when it is rviz's).
 * - A named screen that is not connected: problem "Screen 'X' is not connected", and the automatic
 *   choice (its own problem, if any, appended).
 * - Automatic: among the screens of rviz's X screen (same_x_screen) only, the first that is not
 *   rviz's and not taken; when every such screen is taken, the first of them, with a problem saying
 *   that it is shared with another projector; when there is none besides rviz's, rviz's screen
 *   (shares_rviz_screen). When no screen is marked same_x_screen, rviz's screen (or the first one
 *   when rviz's is unknown), with a problem.
 */
ScreenChoice chooseScreen(const std::vector<ScreenInfo>& screens, int rviz_screen, const std::string& wanted,
                          const std::vector<std::string>& taken);
}  // namespace rviz_projector
