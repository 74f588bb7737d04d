#include "robustness_helpers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <dlfcn.h>
#include <gtest/gtest.h>

#include <OgreCamera.h>
#include <OgreException.h>
#include <OgreManualObject.h>
#include <OgreMaterialManager.h>
#include <OgreRenderTarget.h>
#include <OgreRenderWindow.h>
#include <OgreRoot.h>
#include <OgreSceneManager.h>
#include <OgreSceneNode.h>
#include <QApplication>
#include <QGuiApplication>
#include <QScreen>
#include <QWindow>
#include <rviz/config.h>
#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/visualization_manager.h>
#include <rviz/yaml_config_reader.h>

#include "optical_orientation.h"
#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output_window.h"
#include "rviz_test_fixture.h"

namespace rviz_projector_test
{
using rviz_projector::Vec3;

nav_msgs::Path makePath(const std::string& frame, const std::vector<Vec3>& points, double qx, double qy, double qz,
                        double qw)
{
  nav_msgs::Path path;
  path.header.frame_id = frame;
  path.header.stamp = ros::Time(0);
  path.poses.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    geometry_msgs::PoseStamped& pose = path.poses[i];
    pose.header = path.header;
    pose.pose.position.x = points[i].x;
    pose.pose.position.y = points[i].y;
    pose.pose.position.z = points[i].z;
    pose.pose.orientation.x = qx;
    pose.pose.orientation.y = qy;
    pose.pose.orientation.z = qz;
    pose.pose.orientation.w = qw;
  }
  return path;
}

std::vector<Vec3> line(const Vec3& from, const Vec3& to, std::size_t n)
{
  std::vector<Vec3> points(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const double t = static_cast<double>(i) / static_cast<double>(n - 1);
    points[i] = from + (to - from) * t;
  }
  points.back() = to;
  return points;
}

std::size_t defaultExactArrows(double length)
{
  const double first_tip = 0.10 + 0.05, arrow = 0.10 + 0.08, spacing = 0.25;
  if (first_tip + arrow > length)
  {
    return 0;
  }
  return static_cast<std::size_t>(std::floor((length - first_tip - arrow) / spacing + 1e-9)) + 1;
}

geometry_msgs::TransformStamped projectorMount(const std::string& parent, const std::string& child, double x,
                                               double y, double z, double pitch)
{
  return stampedTransform(parent, child, x, y, z, opticalOrientation(0.0, pitch, 0.0));
}

int projectorWindows(bool visible_only)
{
  int n = 0;
  for (QWidget* w : QApplication::topLevelWidgets())
  {
    if (qobject_cast<rviz_projector::ProjectorOutputWindow*>(w) && (!visible_only || w->isVisible()))
    {
      ++n;
    }
  }
  return n;
}

// libX11 is in the process already (OGRE's GLX uses it): looked up at run time, so that the tests
// need not link it.
bool syncWithTheXServer()
{
  void* display = nullptr;
  auto targets = Ogre::Root::getSingleton().getRenderSystem()->getRenderTargetIterator();
  while (display == nullptr && targets.hasMoreElements())
  {
    Ogre::RenderTarget* target = targets.getNext();
    try
    {
      if (dynamic_cast<Ogre::RenderWindow*>(target) != nullptr)
      {
        target->getCustomAttribute("XDISPLAY", &display);
      }
    }
    catch (const Ogre::Exception&)
    {
      display = nullptr;  // not an X window
    }
  }
  using XSyncFunction = int (*)(void*, int);
  static const auto xsync = reinterpret_cast<XSyncFunction>(dlsym(RTLD_DEFAULT, "XSync"));
  if (display == nullptr || xsync == nullptr)
  {
    return false;
  }
  xsync(display, 0);
  return true;
}

void imageRectangle(int window_width, int window_height, int image_width, int image_height, QRect& rectangle)
{
  // Computed here by hand (the test's own oracle): an image that fits exactly along one axis and
  // is not larger along the other is shown 1:1; otherwise scaled by min(ww / iw, wh / ih), the
  // sizes rounded; centred, the offsets rounded down.
  int w = image_width, h = image_height;
  const bool one_to_one = image_width <= window_width && image_height <= window_height &&
                          (image_width == window_width || image_height == window_height);
  if (!one_to_one)
  {
    const double scale = std::min(double(window_width) / image_width, double(window_height) / image_height);
    w = std::max(1, static_cast<int>(std::lround(image_width * scale)));
    h = std::max(1, static_cast<int>(std::lround(image_height * scale)));
  }
  rectangle = QRect((window_width - w) / 2, (window_height - h) / 2, w, h);
}

QImage grabProjector(rviz_projector::ProjectorCameraDisplay* projector)
{
  rviz_projector::ProjectorOutputWindow* window = projector ? projector->outputWindow() : nullptr;
  if (!window || !window->isVisible())
  {
    return QImage();
  }
  projector->renderNow();
  QApplication::processEvents();
  if (!syncWithTheXServer())
  {
    ADD_FAILURE() << "no X connection behind the projector's render window: cannot tell when it shows a frame";
  }
  QScreen* screen = window->windowHandle() ? window->windowHandle()->screen() : QGuiApplication::primaryScreen();
  const QImage whole = screen->grabWindow(window->winId()).toImage().convertToFormat(QImage::Format_RGB888);
  if (!projector->hasLens())
  {
    return whole;
  }
  QRect image;
  imageRectangle(whole.width(), whole.height(), static_cast<int>(projector->lens().width()),
                 static_cast<int>(projector->lens().height()), image);
  return whole.copy(image);
}

std::string OgreCounts::describe() const
{
  std::ostringstream s;
  s << manual_objects << " manual objects, " << cameras << " cameras, " << scene_nodes << " scene nodes, "
    << render_targets << " render targets, " << materials << " materials";
  return s.str();
}

namespace
{
/// Every scene node the scene manager owns: its own list, not a walk from the root (a node
/// detached from its destroyed parent is not under the root, but is still there: a leak). The
/// list is protected; a pointer to the member taken through a derived class reads it.
struct SceneNodeList : Ogre::SceneManager
{
  static std::size_t count(const Ogre::SceneManager& manager)
  {
    return (manager.*(&SceneNodeList::mSceneNodes)).size();
  }
};
}  // namespace

OgreCounts ogreCounts(Ogre::SceneManager* scene_manager)
{
  OgreCounts c;
  c.manual_objects = scene_manager->getMovableObjects("ManualObject").size();
  c.cameras = scene_manager->getCameras().size();
  c.scene_nodes = SceneNodeList::count(*scene_manager);
  auto targets = Ogre::Root::getSingleton().getRenderSystem()->getRenderTargetIterator();
  while (targets.hasMoreElements())
  {
    ++c.render_targets;
    targets.moveNext();
  }
  std::size_t materials = 0;
  auto it = Ogre::MaterialManager::getSingleton().getResourceIterator();
  while (it.hasMoreElements())
  {
    ++materials;
    it.moveNext();
  }
  c.materials = materials;
  return c;
}

std::size_t residentBytes()
{
  std::ifstream statm("/proc/self/statm");
  std::size_t pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * 4096;
}

bool underAddressSanitizer()
{
#if defined(__SANITIZE_ADDRESS__)
  return true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  return true;
#else
  return false;
#endif
#else
  return false;
#endif
}

std::string loadRvizFile(rviz::VisualizationManager* manager, const QString& file)
{
  rviz::Config config;
  rviz::YamlConfigReader reader;
  reader.readFile(config, file);
  if (reader.error())
  {
    return reader.errorMessage().toStdString();
  }
  manager->load(config.mapGetChild("Visualization Manager"));
  return std::string();
}

std::vector<rviz::Display*> displaysOfClass(rviz::VisualizationManager* manager, const QString& class_id)
{
  std::vector<rviz::Display*> found;
  rviz::DisplayGroup* group = manager->getRootDisplayGroup();
  for (int i = 0; i < group->numDisplays(); ++i)
  {
    if (group->getDisplayAt(i)->getClassId() == class_id)
    {
      found.push_back(group->getDisplayAt(i));
    }
  }
  return found;
}

rviz::Display* displayNamed(rviz::VisualizationManager* manager, const QString& name)
{
  rviz::DisplayGroup* group = manager->getRootDisplayGroup();
  for (int i = 0; i < group->numDisplays(); ++i)
  {
    if (group->getDisplayAt(i)->getName() == name)
    {
      return group->getDisplayAt(i);
    }
  }
  return nullptr;
}

void moveDisplay(rviz::VisualizationManager* manager, rviz::Display* display, int row)
{
  ASSERT_NE(display, nullptr);
  rviz::DisplayGroup* group = manager->getRootDisplayGroup();
  ASSERT_EQ(group->takeDisplay(display), display);
  // DisplayGroup::addChild counts its non-display properties first.
  group->addChild(display, group->rviz::Property::numChildren() + row);
  ASSERT_EQ(group->getDisplayAt(row), display);
}

int screenIndexOf(const QWidget* window)
{
  QScreen* screen = QGuiApplication::screenAt(window->geometry().center());
  return screen ? QGuiApplication::screens().indexOf(screen) : -1;
}

QString configFile(const char* name)
{
  return QString(RVIZ_PROJECTOR_TEST_CONFIGS) + "/" + name;
}
}  // namespace rviz_projector_test
