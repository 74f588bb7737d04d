// rviz's RenderWidget with a complete teardown: its render window is detached from OGRE's root
// and destroyed, so rviz never renders into a window that is gone (removing camera-like displays
// is where rviz plugins historically crash).
#pragma once

#include <rviz/ogre_helpers/render_widget.h>

namespace rviz_projector
{
class ProjectorRenderWidget : public rviz::RenderWidget
{
public:
  explicit ProjectorRenderWidget(QWidget* parent);
  ~ProjectorRenderWidget() override;
};
}  // namespace rviz_projector
