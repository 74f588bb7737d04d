// "Something arrived since the display last looked": raised by a cue source's message callback (on
// the display's private callback queue, drained on rviz's thread), taken by the display once per
// frame to decide whether the picture may have changed at once. Shared by the cue sources.
#pragma once

namespace rviz_projector
{
class NewsFlag
{
public:
  void raise() { raised_ = true; }
  /// Whether it was raised since the last take; lowers it.
  bool take()
  {
    const bool raised = raised_;
    raised_ = false;
    return raised;
  }

private:
  bool raised_ = false;
};
}  // namespace rviz_projector
