#include "host_session.h"

#include <algorithm>

#include <OgreRenderTargetListener.h>
#include <OgreRenderWindow.h>
#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/render_panel.h>
#include <rviz/visualization_manager.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output_window.h"
#include "host_config.h"
#include "host_curtain.h"
#include "host_display_status.h"

namespace rviz_projector
{
namespace
{
/// How much tf history the host keeps (rviz: 10 minutes). Messages older than this cannot be
/// transformed into the fixed frame (a plan stamped more than 30 s ago): README, Running on the robot.
constexpr double kTfCacheSeconds = 30.0;

/// Longest the reload curtain stays up waiting for the new projectors' first frames.
constexpr double kCurtainTimeoutSeconds = 2.0;


/// Counts the frames rendered into a render target.
class FrameCounter : public Ogre::RenderTargetListener
{
public:
  void postRenderTargetUpdate(const Ogre::RenderTargetEvent& /*event*/) override { ++frames; }
  std::uint64_t frames = 0;
};

void collect(rviz::DisplayGroup* group, std::vector<rviz::Display*>& out)
{
  for (int i = 0; i < group->numDisplays(); ++i)
  {
    rviz::Display* display = group->getDisplayAt(i);
    out.push_back(display);
    if (auto* nested = qobject_cast<rviz::DisplayGroup*>(display))
    {
      collect(nested, out);
    }
  }
}
}  // namespace

HostSession::HostSession(const QString& config_path, bool all_displays)
  : path_(config_path), curtain_(std::make_unique<HostCurtain>()), all_displays_(all_displays)
{
  // The main view's panel exists because rviz's manager needs one (view controller, tools); it is
  // never shown and its render window never rendered: rviz's update renders active targets only.
  panel_ = new rviz::RenderPanel();
  // rviz keeps 10 minutes of tf by default, a steady growth (~0.6 MB a minute with a moving robot
  // at 50 Hz) for a history nobody looks at here; displays transform recent messages.
  auto tf_buffer = std::make_shared<tf2_ros::Buffer>(ros::Duration(kTfCacheSeconds));
  auto tf_listener = std::make_shared<tf2_ros::TransformListener>(*tf_buffer, ros::NodeHandle(), true);
  manager_ = new rviz::VisualizationManager(panel_, nullptr, tf_buffer, tf_listener);
  panel_->initialize(manager_->getSceneManager(), manager_);
  manager_->initialize();
  main_view_counter_ = std::make_unique<FrameCounter>();
  if (Ogre::RenderWindow* main_view = panel_->getRenderWindow())
  {
    main_view->setAutoUpdated(false);
    main_view->setActive(false);
    main_view->addListener(main_view_counter_.get());
  }
}

HostSession::~HostSession()
{
  curtain_.reset();
  if (Ogre::RenderWindow* main_view = panel_->getRenderWindow())
  {
    main_view->removeListener(main_view_counter_.get());
  }
  delete manager_;  // deletes the displays: their windows close, the floor goes dark
  delete panel_;
}

HostLoadResult HostSession::start()
{
  return load(true);
}

HostLoadResult HostSession::reload()
{
  return load(false);
}

HostLoadResult HostSession::load(bool first)
{
  HostLoadResult result;
  const HostConfigCheck check =
      checkHostConfig(path_, *manager_->getDisplayFactory(), first ? MissingPlugin::Warn : MissingPlugin::Refuse);
  if (!check.error.empty())
  {
    result.message = first ? check.error : check.error + "; the running configuration is kept";
    return result;
  }
  std::vector<QRect> shown;
  for (ProjectorCameraDisplay* projector : projectors())
  {
    ProjectorOutputWindow* window = projector->outputWindow();
    if (window && window->isVisible())
    {
      shown.push_back(window->frameGeometry());
    }
  }
  curtain_->cover(shown);
  parked_.clear();  // the old displays are deleted by the load
  manager_->load(check.manager_config);
  ++generation_;
  if (!all_displays_)
  {
    parkUnshownDisplays();
  }
  const std::vector<ProjectorCameraDisplay*> now = projectors();
  std::vector<QPointer<ProjectorCameraDisplay>> watched(now.begin(), now.end());
  curtain_->uncoverWhen(
      [watched] {
        for (const QPointer<ProjectorCameraDisplay>& p : watched)
        {
          if (p && p->isEnabled() && p->framesRendered() == 0 && p->hasLens())
          {
            return false;
          }
        }
        return true;
      },
      kCurtainTimeoutSeconds);
  result.ok = true;
  result.warnings = check.warnings;
  result.message = "loaded '" + path_.toStdString() + "': " + std::to_string(check.displays.size()) +
                   " displays, " + std::to_string(check.projectors) + " ProjectorCamera";
  if (!parked_.empty())
  {
    std::string names;
    for (const rviz::Display* display : parked_)
    {
      names += (names.empty() ? "" : ", ") + displayLabel(*display);
    }
    result.message += "; not run, as no ProjectorCamera shows them (--all-displays runs them): " + names;
  }
  Q_EMIT loaded();
  return result;
}

void HostSession::parkUnshownDisplays()
{
  // A display is shown by a ProjectorCamera whose Visibility ticks it: its visibility bits hold the
  // projector's bit (rviz's DisplayVisibilityProperty sets and clears them, groups' ticks included).
  std::uint32_t shown = 0;
  for (ProjectorCameraDisplay* projector : projectors())
  {
    projector->updateVisibilityBits();  // the loaded ticks, before the first render
    shown |= projector->visibilityBit();
  }
  for (rviz::Display* display : displays())
  {
    const bool group = qobject_cast<rviz::DisplayGroup*>(display) != nullptr;
    if (group || qobject_cast<ProjectorCameraDisplay*>(display) || !display->isEnabled() ||
        (display->getVisibilityBits() & shown) != 0)
    {
      continue;  // groups hold displays (each judged by itself); projectors show; shown ones run
    }
    display->setEnabled(false);
    parked_.push_back(display);
  }
}

bool HostSession::parked(const rviz::Display* display) const
{
  return std::find(parked_.begin(), parked_.end(), display) != parked_.end();
}

std::uint64_t HostSession::mainViewFrames() const
{
  return static_cast<const FrameCounter&>(*main_view_counter_).frames;
}

std::vector<rviz::Display*> HostSession::displays() const
{
  std::vector<rviz::Display*> out;
  collect(manager_->getRootDisplayGroup(), out);
  return out;
}

std::vector<ProjectorCameraDisplay*> HostSession::projectors() const
{
  std::vector<ProjectorCameraDisplay*> out;
  for (rviz::Display* display : displays())
  {
    if (auto* projector = qobject_cast<ProjectorCameraDisplay*>(display))
    {
      out.push_back(projector);
    }
  }
  return out;
}
}  // namespace rviz_projector
