// Helpers of the robustness rostests (test/rviz/robustness_*_test.cpp, robustness_fixtures.h): messages with bad values,
// projector mounts, window and Ogre object counts, config loading.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <QImage>
#include <QRect>
#include <QString>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Path.h>
#include <sensor_msgs/CameraInfo.h>

#include "rviz_projector/core/vec3.h"
#include "rviz_test_fixture.h"  // cameraInfo(), countColour()

namespace Ogre
{
class SceneManager;
}
namespace rviz
{
class Display;
class VisualizationManager;
}  // namespace rviz
namespace rviz_projector
{
class ProjectorCameraDisplay;
}
class QWidget;

namespace rviz_projector_test
{
/// Poses at `points` in `frame`, every orientation (qx, qy, qz, qw) as given (not normalised).
nav_msgs::Path makePath(const std::string& frame, const std::vector<rviz_projector::Vec3>& points, double qx = 0.0,
                        double qy = 0.0, double qz = 0.0, double qw = 1.0);
/// `n` >= 2 evenly spaced points from `from` to `to`.
std::vector<rviz_projector::Vec3> line(const rviz_projector::Vec3& from, const rviz_projector::Vec3& to, std::size_t n);
/// Arrows PathSpacer's Exact mode puts on a straight path of `length` with the display's default
/// sizes (spacing 0.25, shaft 0.10 + head 0.08, circle 0.20, gap 0.05).
std::size_t defaultExactArrows(double length);

/// Optical frame of a projector body at (x, y, z) (x forward, z up) pitched down by `pitch`.
geometry_msgs::TransformStamped projectorMount(const std::string& parent, const std::string& child, double x,
                                               double y, double z, double pitch);

/// ProjectorOutputWindows that exist (`visible_only`: that are shown).
int projectorWindows(bool visible_only);
/// Where an image of image_width x image_height is shown in a window (the letterbox), by hand.
void imageRectangle(int window_width, int window_height, int image_width, int image_height, QRect& rectangle);
/// Returns once the X server has processed everything OGRE sent on its connection, the swapped
/// frame included (XSync on that connection, shared by all of OGRE's GLX windows; a grab through
/// Qt's connection then sees the frame). False without such a connection.
bool syncWithTheXServer();
/// Renders the projector view now and reads its window back from the X server (what it shows),
/// letterbox removed.
QImage grabProjector(rviz_projector::ProjectorCameraDisplay* projector);

/// Ogre objects a display creates: compared before and after add/remove cycles.
struct OgreCounts
{
  std::size_t manual_objects = 0;
  std::size_t cameras = 0;
  std::size_t scene_nodes = 0;
  std::size_t render_targets = 0;
  std::size_t materials = 0;
  std::string describe() const;
  bool operator==(const OgreCounts& o) const
  {
    return manual_objects == o.manual_objects && cameras == o.cameras && scene_nodes == o.scene_nodes &&
           render_targets == o.render_targets && materials == o.materials;
  }
};
OgreCounts ogreCounts(Ogre::SceneManager* scene_manager);

/// Resident memory of this process, bytes.
std::size_t residentBytes();
/// True when built with AddressSanitizer (its quarantine makes memory numbers meaningless).
bool underAddressSanitizer();

/// Reads a .rviz file and loads its "Visualization Manager" section, as rviz -d does. Returns
/// an empty string or the reader's error.
std::string loadRvizFile(rviz::VisualizationManager* manager, const QString& file);
/// Displays of the root group with this class id, in order.
std::vector<rviz::Display*> displaysOfClass(rviz::VisualizationManager* manager, const QString& class_id);
/// Display of the root group named `name` (nullptr if none).
rviz::Display* displayNamed(rviz::VisualizationManager* manager, const QString& name);
/// Moves `display` to `row` of the root display group, as drag and drop in the Displays panel.
void moveDisplay(rviz::VisualizationManager* manager, rviz::Display* display, int row);
/// Index in QGuiApplication::screens() of the screen holding the centre of `window` (-1: none).
int screenIndexOf(const QWidget* window);
/// Path of a file in test/rviz/configs.
QString configFile(const char* name);
}  // namespace rviz_projector_test
