#include "rviz_projector/core/screen_choice.h"

#include <algorithm>

namespace rviz_projector
{
namespace
{
bool isTaken(const std::vector<std::string>& taken, const std::string& name)
{
  return std::find(taken.begin(), taken.end(), name) != taken.end();
}

ScreenChoice automaticChoice(const std::vector<ScreenInfo>& screens, int rviz_screen,
                             const std::vector<std::string>& taken)
{
  ScreenChoice choice;
  int first_shared = -1;
  for (int i = 0; i < static_cast<int>(screens.size()); ++i)
  {
    if (i == rviz_screen || !screens[i].same_x_screen)
    {
      continue;
    }
    if (!isTaken(taken, screens[i].name))
    {
      choice.index = i;
      return choice;
    }
    if (first_shared < 0)
    {
      first_shared = i;
    }
  }
  if (first_shared >= 0)
  {
    choice.index = first_shared;
    choice.problem = "Every other screen is already used by another projector: sharing screen '" +
                     screens[first_shared].name + "' with another projector";
    return choice;
  }
  if (rviz_screen >= 0)
  {
    // Only rviz's own screen (e.g. a laptop without the projector plugged in).
    choice.index = rviz_screen;
    choice.shares_rviz_screen = true;
    return choice;
  }
  // rviz's screen is unknown and no screen is marked as its sibling: the first screen there is.
  choice.index = 0;
  choice.problem = "No screen of rviz's X screen is known: using screen '" + screens[0].name + "'";
  return choice;
}
}  // namespace

ScreenChoice chooseScreen(const std::vector<ScreenInfo>& screens, int rviz_screen, const std::string& wanted,
                          const std::vector<std::string>& taken)
{
  ScreenChoice choice;
  if (screens.empty())
  {
    choice.problem = "No screen is connected";
    return choice;
  }
  if (rviz_screen >= static_cast<int>(screens.size()) || rviz_screen < -1)
  {
    rviz_screen = -1;  // not one of these screens: unknown
  }
  const bool automatic = wanted.empty() || wanted == kAutomaticScreen;
  if (!automatic)
  {
    for (int i = 0; i < static_cast<int>(screens.size()); ++i)
    {
      if (screens[i].name == wanted)
      {
        choice.index = i;
        choice.shares_rviz_screen = i == rviz_screen;
        return choice;
      }
    }
  }
  choice = automaticChoice(screens, rviz_screen, taken);
  choice.shares_rviz_screen = choice.index >= 0 && choice.index == rviz_screen;
  if (!automatic)
  {
    const std::string missing = "Screen '" + wanted + "' is not connected";
    choice.problem = choice.problem.empty() ? missing : missing + "; " + choice.problem;
  }
  return choice;
}
}  // namespace rviz_projector
