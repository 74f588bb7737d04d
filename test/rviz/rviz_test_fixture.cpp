#include "rviz_test_fixture.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <OgreMaterialManager.h>
#include <OgreRenderWindow.h>
#include <QApplication>
#include <QTemporaryDir>
#include <QThread>
#include <geometry_msgs/TransformStamped.h>
#include <rviz/config.h>
#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/properties/status_list.h>
#include <rviz/render_panel.h>
#include <rviz/view_controller.h>
#include <rviz/view_manager.h>
#include <rviz/visualization_manager.h>
#include <rviz/yaml_config_reader.h>
#include <rviz/yaml_config_writer.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include "rviz_projector/displays/render_target_readback.h"

namespace rviz_projector_test
{
RvizInstance::RvizInstance(int width, int height)
{
  panel_ = new rviz::RenderPanel();
  panel_->resize(width, height);
  panel_->show();
  manager_ = new rviz::VisualizationManager(panel_);
  panel_->initialize(manager_->getSceneManager(), manager_);
  manager_->initialize();
  manager_->setFixedFrame("map");
  manager_->startUpdate();
  QApplication::processEvents();
}

RvizInstance::~RvizInstance()
{
  delete manager_;
  delete panel_;
  QApplication::processEvents();
  // VisualizationManager::initialize() creates these process-wide without checking whether they
  // exist and its destructor leaves them: remove them so that a later instance can be created.
  for (const char* name : {"RVIZ/Red", "RVIZ/Green", "RVIZ/Blue", "RVIZ/Cyan", "RVIZ/ShadedRed", "RVIZ/ShadedGreen",
                           "RVIZ/ShadedBlue", "RVIZ/ShadedCyan"})
  {
    Ogre::MaterialPtr material = Ogre::MaterialManager::getSingleton().getByName(name);
    if (material)
    {
      Ogre::MaterialManager::getSingleton().remove(material);
    }
  }
}

rviz::Display* RvizInstance::addDisplay(const QString& class_id, const QString& name)
{
  return manager_->createDisplay(class_id, name, true);
}

void RvizInstance::setTopDownView(double x, double y, double pixels_per_metre)
{
  manager_->getViewManager()->setCurrentViewControllerType("rviz/TopDownOrtho");
  rviz::ViewController* view = manager_->getViewManager()->getCurrent();
  view->subProp("Scale")->setValue(pixels_per_metre);
  view->subProp("X")->setValue(x);
  view->subProp("Y")->setValue(y);
  view->subProp("Angle")->setValue(0.0);
  view_x_ = x;
  view_y_ = y;
  scale_ = pixels_per_metre;
}

QPoint RvizInstance::topDownPixel(double x, double y) const
{
  // TopDownOrtho at angle 0: +x to the right, +y up, the centre at the middle of the panel.
  const double cx = panel_->getRenderWindow()->getWidth() / 2.0;
  const double cy = panel_->getRenderWindow()->getHeight() / 2.0;
  return QPoint(static_cast<int>(std::floor(cx + (x - view_x_) * scale_)),
                static_cast<int>(std::floor(cy - (y - view_y_) * scale_)));
}

QImage RvizInstance::renderMainView()
{
  Ogre::RenderWindow* window = panel_->getRenderWindow();
  window->update(false);
  std::vector<std::uint8_t> rgb;
  unsigned w = 0, h = 0;
  rviz_projector::readRgbPixels(window, rgb, w, h);
  window->swapBuffers();
  QImage image(rgb.data(), static_cast<int>(w), static_cast<int>(h), static_cast<int>(w) * 3, QImage::Format_RGB888);
  return image.copy();
}

void RvizTest::SetUp()
{
  static_tf_ = std::make_unique<tf2_ros::StaticTransformBroadcaster>();
  rviz_ = std::make_unique<RvizInstance>(640, 480);
}

void RvizTest::TearDown()
{
  rviz_.reset();
  static_tf_.reset();
}

void RvizTest::spinFor(double seconds)
{
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
  while (ros::WallTime::now() < end)
  {
    QApplication::processEvents(QEventLoop::AllEvents, 5);
    ros::spinOnce();
    QThread::msleep(2);
  }
}

bool RvizTest::waitFor(const std::function<bool()>& done, double timeout)
{
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
  while (!done() && ros::WallTime::now() < end)
  {
    spinFor(0.01);
  }
  return done();
}

bool RvizTest::waitForMainViewFrames(int frames, double timeout)
{
  const std::uint64_t start = rviz_->manager()->getFrameCount();
  return waitFor([&] { return rviz_->manager()->getFrameCount() >= start + std::uint64_t(frames); }, timeout);
}

Status RvizTest::statusOf(rviz::Display* display, const QString& name)
{
  // Display::setStatus() is queued: deliver what is pending first.
  QCoreApplication::sendPostedEvents(nullptr, QEvent::MetaCall);
  Status status;
  for (int i = 0; i < display->numChildren(); ++i)
  {
    auto* list = dynamic_cast<rviz::StatusList*>(display->childAt(i));
    if (!list)
    {
      continue;
    }
    for (int j = 0; j < list->numChildren(); ++j)
    {
      auto* item = dynamic_cast<rviz::StatusProperty*>(list->childAt(j));
      if (item && item->getName() == name)
      {
        status.present = true;
        status.level = item->getLevel();
        status.text = item->getValue().toString();
      }
    }
  }
  return status;
}

void RvizTest::publishStaticTransform(const std::string& parent, const std::string& child, double x, double y,
                                      double z, double yaw)
{
  static_tf_->sendTransform(stampedTransform(parent, child, x, y, z, fromRollPitchYaw(0.0, 0.0, yaw)));
}

geometry_msgs::TransformStamped stampedTransform(const std::string& parent, const std::string& child, double x,
                                                double y, double z, const Quaternion& rotation)
{
  geometry_msgs::TransformStamped t;
  t.header.stamp = ros::Time::now();
  t.header.frame_id = parent;
  t.child_frame_id = child;
  t.transform.translation.x = x;
  t.transform.translation.y = y;
  t.transform.translation.z = z;
  t.transform.rotation.x = rotation.x;
  t.transform.rotation.y = rotation.y;
  t.transform.rotation.z = rotation.z;
  t.transform.rotation.w = rotation.w;
  return t;
}

bool sameColour(QRgb a, QRgb b, int tolerance)
{
  return std::abs(qRed(a) - qRed(b)) <= tolerance && std::abs(qGreen(a) - qGreen(b)) <= tolerance &&
         std::abs(qBlue(a) - qBlue(b)) <= tolerance;
}

int countColour(const QImage& image, QRgb colour, int tolerance)
{
  int n = 0;
  for (int y = 0; y < image.height(); ++y)
  {
    for (int x = 0; x < image.width(); ++x)
    {
      n += sameColour(image.pixel(x, y), colour, tolerance) ? 1 : 0;
    }
  }
  return n;
}

sensor_msgs::CameraInfo cameraInfo(const std::string& frame, unsigned w, unsigned h, double f, double cx, double cy)
{
  sensor_msgs::CameraInfo info;
  info.header.frame_id = frame;
  info.width = w;
  info.height = h;
  info.distortion_model = "plumb_bob";
  info.D = {0, 0, 0, 0, 0};
  info.K = {f, 0, cx, 0, f, cy, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {f, 0, cx, 0, 0, f, cy, 0, 0, 0, 1, 0};
  return info;
}

std::string describe(QRgb c)
{
  return std::to_string(qRed(c)) + "," + std::to_string(qGreen(c)) + "," + std::to_string(qBlue(c));
}
ros::Time monotonicTestStart(double multiple)
{
  static double last = 0.0;
  const double now = multiple * std::floor(ros::WallTime::now().toSec() / multiple);
  last = std::max(now, multiple * std::ceil((last + 2.0) / multiple));
  return ros::Time(last);
}
namespace
{
/// `group`'s property at `path`: child names joined by '/' ("Speed-coded spacing/Time step").
rviz::Property* descendant(rviz::Property* group, const std::string& path)
{
  rviz::Property* p = group;
  for (const QString& name : QString::fromStdString(path).split('/'))
  {
    p = p == nullptr ? nullptr : p->subProp(name);
  }
  return p;
}
}  // namespace

std::map<std::string, std::string> RvizTest::expectGroupSavedAndLoaded(const QString& group_name,
                                                                     const std::map<std::string, QVariant>& values,
                                                                     const QString& class_id)
{
  std::map<std::string, std::string> shown;
  rviz::Display* d = rviz_->addDisplay(class_id, "Saved display");
  EXPECT_NE(d, nullptr);
  if (d == nullptr)
  {
    return shown;
  }
  rviz::Property* group = d->subProp(group_name);
  for (const auto& v : values)
  {
    descendant(group, v.first)->setValue(v.second);
  }
  group->setValue(true);
  for (const auto& v : values)
  {
    shown[v.first] = descendant(group, v.first)->getValue().toString().toStdString();
  }
  QTemporaryDir dir;
  const QString file = dir.path() + "/saved.rviz";
  rviz::Config saved;
  rviz_->manager()->save(saved);
  rviz::YamlConfigWriter().writeFile(saved, file);
  rviz_.reset();  // close this rviz before starting the next

  RvizInstance fresh(320, 240);
  rviz::Config loaded;
  rviz::YamlConfigReader reader;
  reader.readFile(loaded, file);
  EXPECT_FALSE(reader.error()) << reader.errorMessage().toStdString();
  fresh.manager()->load(loaded);
  EXPECT_EQ(fresh.manager()->getRootDisplayGroup()->numDisplays(), 1);
  if (fresh.manager()->getRootDisplayGroup()->numDisplays() != 1)
  {
    return shown;
  }
  rviz::Property* again = fresh.manager()->getRootDisplayGroup()->getDisplayAt(0)->subProp(group_name);
  EXPECT_TRUE(again->getValue().toBool()) << "the group's switch";
  for (const auto& v : shown)
  {
    EXPECT_EQ(descendant(again, v.first)->getValue().toString().toStdString(), v.second) << v.first;
  }
  return shown;
}
}  // namespace rviz_projector_test
