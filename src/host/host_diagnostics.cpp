#include "host_diagnostics.h"

#include <algorithm>

#include <OgreMaterialManager.h>
#include <OgreMeshManager.h>
#include <OgreSceneManager.h>
#include <OgreSceneNode.h>
#include <OgreTextureManager.h>
#include <QPointer>
#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/visualization_manager.h>
#include <rviz/properties/status_property.h>

#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/ros_clock.h"
#include "host_display_status.h"
#include "host_projector_status.h"
#include "host_session.h"

namespace rviz_projector
{
namespace
{
/// How often the updater is given a chance to publish (it publishes at ~diagnostic_period, 1 s).
constexpr int kPollMs = 100;

unsigned char diagnosticLevel(int rviz_level)
{
  switch (rviz_level)
  {
    case rviz::StatusProperty::Ok:
      return diagnostic_msgs::DiagnosticStatus::OK;
    case rviz::StatusProperty::Warn:
      return diagnostic_msgs::DiagnosticStatus::WARN;
    default:
      return diagnostic_msgs::DiagnosticStatus::ERROR;
  }
}

struct OgreResourceCounts
{
  std::size_t meshes = 0, materials = 0, textures = 0, scene_nodes = 0;
};

/// Every scene node the scene manager owns: its own list, not a walk from the root (a node detached
/// from a destroyed parent is under no root but still there: exactly the leak a soak looks for).
/// OGRE 1.12 keeps the list protected; a member pointer taken through a derived class reads it.
struct SceneNodeList : Ogre::SceneManager
{
  static std::size_t count(const Ogre::SceneManager& manager) { return (manager.*(&SceneNodeList::mSceneNodes)).size(); }
};

std::size_t resourceCount(Ogre::ResourceManager& manager)
{
  std::size_t n = 0;
  for (auto it = manager.getResourceIterator(); it.hasMoreElements(); it.moveNext())
  {
    ++n;
  }
  return n;
}

/// What a soak watches for leaks: OGRE's resources and the scene graph.
OgreResourceCounts ogreResourceCounts(Ogre::SceneManager* scene)
{
  OgreResourceCounts counts;
  counts.meshes = resourceCount(Ogre::MeshManager::getSingleton());
  counts.materials = resourceCount(Ogre::MaterialManager::getSingleton());
  counts.textures = resourceCount(Ogre::TextureManager::getSingleton());
  counts.scene_nodes = scene ? SceneNodeList::count(*scene) : 0;
  return counts;
}
}  // namespace

HostDiagnostics::HostDiagnostics(HostSession& session) : session_(session)
{
  updater_.setHardwareID("projector_host");
  connect(&session_, &HostSession::loaded, this, &HostDiagnostics::rebuild);
  connect(&timer_, &QTimer::timeout, this, [this] {
    // diagnostic_updater waits until ROS time reaches its next publish time: after a backward jump
    // of ROS time (a bag loop) that time lies in the future, and it would publish nothing until the
    // bag came back there. A jump publishes at once and starts its schedule anew.
    if (epoch_.changed(RosClock::shared().tick()))
    {
      updater_.force_update();
      return;
    }
    updater_.update();
  });
  timer_.start(kPollMs);
  rebuild();
}

HostDiagnostics::~HostDiagnostics() = default;

void HostDiagnostics::setLastLoad(const HostLoadResult& result)
{
  last_ok_ = result.ok;
  last_message_ = result.message;
  if (result.ok)
  {
    last_warnings_ = result.warnings;
  }
}

void HostDiagnostics::rebuild()
{
  for (const std::string& name : task_names_)
  {
    updater_.removeByName(name);
  }
  task_names_.clear();
  task_names_.push_back("config");
  updater_.add(task_names_.back(), this, &HostDiagnostics::configStatus);
  task_names_.push_back("displays");
  updater_.add(task_names_.back(), this, &HostDiagnostics::displaysStatus);
  for (ProjectorCameraDisplay* projector : session_.projectors())
  {
    QPointer<ProjectorCameraDisplay> watched(projector);
    task_names_.push_back(projector->getName().toStdString());
    updater_.add(task_names_.back(), [watched](diagnostic_updater::DiagnosticStatusWrapper& status) {
      if (!watched)
      {
        status.summary(diagnostic_msgs::DiagnosticStatus::STALE, "display was removed");
        return;
      }
      fillProjectorStatus(*watched, displayStatusLines(*watched), status);
    });
  }
}

void HostDiagnostics::configStatus(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  unsigned char level = diagnostic_msgs::DiagnosticStatus::OK;
  if (!last_ok_ || !last_warnings_.empty())
  {
    level = diagnostic_msgs::DiagnosticStatus::WARN;
  }
  status.summary(level, last_ok_ ? (last_warnings_.empty() ? "configuration running" :
                                                             "configuration running, some displays skipped") :
                                   "last reload refused: " + last_message_);
  status.add("Config file", session_.configPath().toStdString());
  status.add("Main view frames", session_.mainViewFrames());
  const OgreResourceCounts ogre = ogreResourceCounts(session_.manager()->getSceneManager());
  status.add("OGRE meshes", ogre.meshes);
  status.add("OGRE materials", ogre.materials);
  status.add("OGRE textures", ogre.textures);
  status.add("OGRE scene nodes", ogre.scene_nodes);
  status.add("Loads", session_.generation());
  status.add("Last load", last_message_);
  for (std::size_t i = 0; i < last_warnings_.size(); ++i)
  {
    status.add("Skipped " + std::to_string(i + 1), last_warnings_[i]);
  }
}

void HostDiagnostics::displaysStatus(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  int worst = rviz::StatusProperty::Ok;
  std::string worst_text = "all displays OK";
  int count = 0;
  for (rviz::Display* display : session_.displays())
  {
    if (qobject_cast<ProjectorCameraDisplay*>(display))
    {
      continue;  // in its own status
    }
    ++count;
    const std::string label = displayLabel(*display);
    status.add(label, session_.parked(display) ? std::string(kParkedDisplay)
                      : display->isEnabled()     ? "enabled"
                                                 : "disabled");
    for (const DisplayStatusLine& line : displayStatusLines(*display))
    {
      status.add(label + " / " + line.name, line.text);
      if (display->isEnabled() && line.level > worst)
      {
        worst = line.level;
        worst_text = label + ": " + line.name + ": " + line.text;
      }
    }
  }
  if (session_.manager())
  {
    for (const DisplayStatusLine& line : displayStatusLines(*session_.manager()->getRootDisplayGroup()))
    {
      status.add("Global Status / " + line.name, line.text);
      if (line.level > worst)
      {
        worst = line.level;
        worst_text = "Global Status: " + line.name + ": " + line.text;
      }
    }
  }
  status.add("Displays", count);
  status.summary(diagnosticLevel(worst), worst_text);
}
}  // namespace rviz_projector
