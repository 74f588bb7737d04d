// Heap allocations per projector frame (issue 11, defect 11), in a real rviz (VisualizationManager
// + RenderPanel, as the rviz tests create it) with a ProjectorCamera full screen on the projector
// screen and a ProjectedPath it shows. malloc and its relatives are replaced in this executable
// (every library's calls land here) and count the calls made on the main thread while counting is
// on, i.e. inside the measured calls only.
//
// Measured per frame, in steady state (after warm-up frames):
//   steady       nothing changes; ProjectorCameraDisplay::renderNow() finds nothing to render
//   same-scene   nothing visible changes but a render is asked for every frame (another display of
//                this package said it changed: ProjectionChangeCounter)
//   driving      the projector's pose changes every frame (the robot drives and turns)
//   ogre-only    the same output window rendered by OGRE alone (RenderWindow::update + swap, with
//                the display's preRenderTargetUpdate): what OGRE and the GL driver allocate on the
//                main thread, for comparison
//   frame-clock  the display's per-tick bookkeeping (ProjectorFrameClock::frameDone: the frame
//                rate meter's sample), outside renderNow()
//   same-scene-warped, driving-warped  (issue 24) the same through a wide-angle lens (k1 = -0.2,
//                k2 = 0.05): the ideal view rendered to a texture and warped into the window,
//                the warp's cells chosen as the renderer makes them (auto: on llvmpipe only the
//                cells with something on them, read back from the ideal render)
//   same-scene-warped-all, driving-warped-all  the same with every cell of the warp drawn
//                (RVIZ_PROJECTOR_WARP_CELLS=all: what a GPU does)
//   paired same-scene, paired driving  the warp's extra CPU per frame measured in pairs: blocks of
//                N/6 frames without D and with it alternate six times and each pair's difference of
//                medians is printed (rows a minute apart see a shared VM at different speeds)
// and the process RSS before and after the N frames of each, and the wall time of the measured
// call per frame (median, 95th percentile) and its CPU time (median; the whole process: llvmpipe
// shades on threads of its own): the warp's cost is the warped row minus the same row without D,
// in the same run (the counting allocator's overhead is in both).
//
// Run by scripts/bench --alloc (a ROS master and an X server; the two-screen Xorg dummy server
// puts the projector window full screen on its own 1280x800 screen).
#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <ctime>
#include <cerrno>
#include <csignal>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <OgreRenderWindow.h>
#include <QApplication>
#include <QElapsedTimer>
#include <QThread>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <rviz/display.h>
#include <rviz/properties/status_list.h>
#include <rviz/render_panel.h>
#include <rviz/visualization_manager.h>
#include <sensor_msgs/CameraInfo.h>
#include <tf2/LinearMath/Transform.h>
#include <tf2_ros/buffer.h>

#include "rviz_projector/displays/projection_change_counter.h"
#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_frame_clock.h"
#include "rviz_projector/displays/projector_output_window.h"

// ---- counting allocator ---------------------------------------------------------------------
extern "C" {
void* __libc_malloc(size_t size);
void* __libc_calloc(size_t n, size_t size);
void* __libc_realloc(void* p, size_t size);
void* __libc_memalign(size_t alignment, size_t size);
void __libc_free(void* p);
}

namespace
{
thread_local bool t_counting = false;  // initial-exec TLS of the executable: no allocation
std::atomic<std::uint64_t> g_allocations{0};
std::atomic<std::uint64_t> g_bytes{0};
/// RP_ALLOC_TRAP=1: stop (SIGTRAP) at the first counted allocation, to see its caller in gdb.
const bool g_trap = std::getenv("RP_ALLOC_TRAP") != nullptr;

inline void count(size_t size)
{
  if (t_counting)
  {
    if (g_trap)
    {
      t_counting = false;
      std::raise(SIGTRAP);
    }
    g_allocations.fetch_add(1, std::memory_order_relaxed);
    g_bytes.fetch_add(size, std::memory_order_relaxed);
  }
}
}  // namespace

extern "C" {
void* malloc(size_t size) noexcept
{
  count(size);
  return __libc_malloc(size);
}
void* calloc(size_t n, size_t size) noexcept
{
  count(n * size);
  return __libc_calloc(n, size);
}
void* realloc(void* p, size_t size) noexcept
{
  count(size);
  return __libc_realloc(p, size);
}
void* memalign(size_t alignment, size_t size) noexcept
{
  count(size);
  return __libc_memalign(alignment, size);
}
void* aligned_alloc(size_t alignment, size_t size) noexcept
{
  count(size);
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, size_t alignment, size_t size) noexcept
{
  count(size);
  void* p = __libc_memalign(alignment, size);
  if (!p)
  {
    return ENOMEM;
  }
  *out = p;
  return 0;
}
void free(void* p) noexcept
{
  __libc_free(p);
}
}

namespace
{
using rviz_projector::ProjectorCameraDisplay;

struct Counted
{
  std::uint64_t allocations = 0;
  std::uint64_t bytes = 0;
};

/// Runs `f` with counting on (main thread only) and returns what it allocated.
template <typename F>
Counted counted(F f)
{
  const std::uint64_t a0 = g_allocations.load(), b0 = g_bytes.load();
  t_counting = true;
  f();
  t_counting = false;
  return { g_allocations.load() - a0, g_bytes.load() - b0 };
}

double rssMiB()
{
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

void spin(double seconds)
{
  QElapsedTimer clock;
  clock.start();
  do
  {
    QApplication::processEvents(QEventLoop::AllEvents, 5);
    ros::spinOnce();
    QThread::msleep(2);
  } while (clock.nsecsElapsed() < static_cast<qint64>(seconds * 1e9));
}

template <typename Done>
bool waitFor(Done done, double timeout)
{
  QElapsedTimer clock;
  clock.start();
  while (!done() && clock.nsecsElapsed() < static_cast<qint64>(timeout * 1e9))
  {
    spin(0.01);
  }
  return done();
}

/// The projector's optical frame at (x, y, 1.2 m), looking along `yaw`, pitched down 0.9 rad.
geometry_msgs::TransformStamped projectorPose(const std::string& child, double x, double y, double yaw,
                                              const ros::Time& stamp)
{
  const double c = std::cos(0.9), s = std::sin(0.9);
  // Optical axes in the robot frame: x right, y down, z forward (and down by the pitch).
  const tf2::Matrix3x3 optical(0, -s, c, -1, 0, 0, 0, -c, -s);
  tf2::Matrix3x3 turn;
  turn.setRPY(0, 0, yaw);
  tf2::Quaternion q;
  (turn * optical).getRotation(q);
  geometry_msgs::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = "map";
  t.child_frame_id = child;
  t.transform.translation.x = x;
  t.transform.translation.y = y;
  t.transform.translation.z = 1.2;
  t.transform.rotation.x = q.x();
  t.transform.rotation.y = q.y();
  t.transform.rotation.z = q.z();
  t.transform.rotation.w = q.w();
  return t;
}

struct Row
{
  std::string name;
  int frames = 0;
  std::uint64_t rendered = 0;
  Counted total;
  double rss_before = 0, rss_after = 0;
  std::vector<double> ms;      // wall time of each measured call
  std::vector<double> cpu_ms;  // CPU time of the process (every thread: the GL driver's too)
};

// CPU time of the whole process, ms: Mesa's llvmpipe shades on threads of its own, and the main
// thread waits for them; on a shared machine this varies far less with the load than wall time.
double processCpuMs()
{
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

double percentile(std::vector<double> values, double q)
{
  if (values.empty())
  {
    return 0.0;
  }
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(q * static_cast<double>(values.size() - 1) + 0.5)];
}

void print(const Row& r)
{
  std::printf("%-18s %7d %9llu %12.2f %12.1f %10.1f %10.1f %+9.2f %9.3f %9.3f %9.3f\n", r.name.c_str(), r.frames,
              static_cast<unsigned long long>(r.rendered), static_cast<double>(r.total.allocations) / r.frames,
              static_cast<double>(r.total.bytes) / r.frames, r.rss_before, r.rss_after, r.rss_after - r.rss_before,
              percentile(r.ms, 0.5), percentile(r.ms, 0.95), percentile(r.cpu_ms, 0.5));
  std::fflush(stdout);
}
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "alloc_bench", ros::init_options::AnonymousName);
  QApplication app(argc, argv);
  int frames = 600;
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (std::strcmp(argv[i], "--frames") == 0)
    {
      frames = std::max(10, std::atoi(argv[i + 1]));
    }
  }
  const int warmup = 120;
  ros::NodeHandle nh;

  auto* panel = new rviz::RenderPanel();
  panel->resize(640, 480);
  panel->show();
  auto* manager = new rviz::VisualizationManager(panel);
  panel->initialize(manager->getSceneManager(), manager);
  manager->initialize();
  manager->setFixedFrame("map");
  manager->startUpdate();

  auto* path_display = manager->createDisplay("rviz_projector/ProjectedPath", "Path", true);
  path_display->subProp("Topic")->setValue("/alloc_bench/plan");
  auto* projector = dynamic_cast<ProjectorCameraDisplay*>(
      manager->createDisplay("rviz_projector/ProjectorCamera", "Projector", true));
  if (!projector)
  {
    std::fprintf(stderr, "alloc_bench: no ProjectorCamera display (is the workspace sourced?)\n");
    return 1;
  }
  projector->subProp("Topic")->setValue("/alloc_bench/camera_info");
  projector->subProp("Frame")->setValue("alloc_bench_fixed");

  tf2_ros::Buffer& tf = *manager->getTF2BufferPtr();
  tf.setTransform(projectorPose("alloc_bench_fixed", 0.0, 0.0, 0.0, ros::Time(0)), "alloc_bench", true);

  ros::Publisher info_pub = nh.advertise<sensor_msgs::CameraInfo>("/alloc_bench/camera_info", 1, true);
  sensor_msgs::CameraInfo info;
  info.header.frame_id = "alloc_bench_fixed";
  info.width = 1280;
  info.height = 800;
  info.distortion_model = "plumb_bob";
  info.D = { 0, 0, 0, 0, 0 };
  info.K = { 1300, 0, 639.5, 0, 1300, 399.5, 0, 0, 1 };
  info.R = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  info.P = { 1300, 0, 639.5, 0, 0, 1300, 399.5, 0, 0, 0, 1, 0 };
  info_pub.publish(info);

  // A path ahead of the robot: a few arrows and the destination circle in the projector's view.
  ros::Publisher path_pub = nh.advertise<nav_msgs::Path>("/alloc_bench/plan", 1, true);
  nav_msgs::Path path;
  path.header.frame_id = "map";
  for (int i = 0; i <= 20; ++i)
  {
    geometry_msgs::PoseStamped p;
    p.header = path.header;
    p.pose.position.x = 0.5 + 0.1 * i;
    p.pose.position.y = 0.02 * i;
    p.pose.orientation.w = 1;
    path.poses.push_back(p);
  }
  path_pub.publish(path);

  if (!waitFor([&] { return projector->hasLens() && projector->outputWindow() && projector->outputWindow()->isVisible(); },
               15.0))
  {
    std::fprintf(stderr, "alloc_bench: the projector got no CameraInfo or shows no window\n");
    return 1;
  }
  spin(2.0);
  const Ogre::RenderWindow* rw = projector->outputWindow()->renderWindow();
  std::printf("# output window %ux%u%s, %d frames per row after %d warm-up frames\n", rw->getWidth(),
              rw->getHeight(), projector->outputWindow()->isFullScreenOn() ? " full screen" : " windowed", frames,
              warmup);
  std::printf("%-18s %7s %9s %12s %12s %10s %10s %9s %9s %9s %9s\n", "scenario", "frames", "rendered",
              "allocs/frame", "bytes/frame", "RSS0 MiB", "RSS1 MiB", "dRSS MiB", "ms med", "ms p95", "cpu med");

  // One scenario: `before` runs uncounted before each frame (events, tf), `frame` is counted.
  auto run = [&](const std::string& name, auto before, auto frame) {
    Row row;
    row.name = name;
    row.frames = frames;
    for (int i = 0; i < warmup; ++i)
    {
      spin(0.0);
      before(i);
      frame();
    }
    row.rss_before = rssMiB();
    for (int i = 0; i < frames; ++i)
    {
      spin(0.0);  // rviz's own update and the display's frame clock run here, uncounted
      before(warmup + i);
      const std::uint64_t r0 = projector->framesRendered();
      const auto t0 = std::chrono::steady_clock::now();
      const double cpu0 = processCpuMs();
      const Counted c = counted(frame);
      row.cpu_ms.push_back(processCpuMs() - cpu0);
      row.ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      row.rendered += projector->framesRendered() - r0;
      row.total.allocations += c.allocations;
      row.total.bytes += c.bytes;
    }
    row.rss_after = rssMiB();
    print(row);
  };
  auto render_now = [&] { projector->renderNow(); };
  // 0.5 m/s along a gentle curve at 60 frames/s.
  auto drive = [&](int i) {
    const double t = i / 60.0;
    tf.setTransform(projectorPose("alloc_bench_driving", 0.5 * t, 0.1 * std::sin(0.5 * t), 0.2 * std::sin(0.3 * t),
                                  ros::Time::now()),
                    "alloc_bench", false);
  };

  run("steady", [](int) {}, render_now);
  run("same-scene", [](int) { rviz_projector::ProjectionChangeCounter::bump(); }, render_now);
  projector->subProp("Frame")->setValue("alloc_bench_driving");
  run("driving", drive, render_now);
  Ogre::RenderWindow* window = projector->outputWindow()->renderWindow();
  run("ogre-only", [](int) {},
      [&] {
        window->update(false);
        window->swapBuffers();
      });
  rviz_projector::ProjectorFrameClock clock;
  std::uint64_t ticks = 0;
  run("frame-clock", [](int) {}, [&] { clock.frameDone(++ticks, false); });

  // Issue 24: the same through a wide-angle lens (the warp: texture + mesh pass), first with every
  // cell of the mesh drawn, then as the renderer makes it (auto).
  // The projector says it draws through the lens: its "Distortion" status (null when absent).
  auto distortionStatus = [&]() -> rviz::StatusProperty* {
    for (int i = 0; i < projector->numChildren(); ++i)
    {
      if (auto* list = dynamic_cast<rviz::StatusList*>(projector->childAt(i)))
      {
        for (int j = 0; j < list->numChildren(); ++j)
        {
          auto* status = dynamic_cast<rviz::StatusProperty*>(list->childAt(j));
          if (status && status->getName() == "Distortion")
          {
            return status;
          }
        }
      }
    }
    return nullptr;
  };
  const sensor_msgs::CameraInfo plain = info;
  for (const char* cells : {"all", "auto"})
  {
    info_pub.publish(plain);  // no D: the warp released, made anew below with `cells`
    if (!waitFor([&] { return distortionStatus() == nullptr; }, 5.0))
    {
      std::fprintf(stderr, "alloc_bench: the projector still draws through a lens without D\n");
      return 1;
    }
    setenv("RVIZ_PROJECTOR_WARP_CELLS", cells, 1);
    info.D = { -0.2, 0.05, 0, 0, 0 };
    info_pub.publish(info);
    auto warped = [&] {
      const rviz::StatusProperty* status = distortionStatus();
      return status && status->getLevel() == rviz::StatusProperty::Ok;
    };
    if (!waitFor(warped, 5.0))
    {
      std::fprintf(stderr, "alloc_bench: the projector does not draw through the distorted lens\n");
      return 1;
    }
    std::fprintf(stderr, "alloc_bench: %s\n", distortionStatus()->getValue().toString().toStdString().c_str());
    spin(1.0);
    const std::string suffix = std::string(cells) == "all" ? "-all" : "";
    projector->subProp("Frame")->setValue("alloc_bench_fixed");
    run(("same-scene-warped" + suffix).c_str(), [](int) { rviz_projector::ProjectionChangeCounter::bump(); },
        render_now);
    projector->subProp("Frame")->setValue("alloc_bench_driving");
    run(("driving-warped" + suffix).c_str(), drive, render_now);
  }
  unsetenv("RVIZ_PROJECTOR_WARP_CELLS");

  // The warp's extra CPU per frame, paired: short blocks of frames without D and with it (cells as
  // the renderer chooses), alternating, so both halves of a pair see the same machine (on a shared
  // VM the speed drifts by more than the warp costs between rows a minute apart). Per pair the
  // difference of the two blocks' median process CPU; printed per pair and their median.
  const int block = std::max(20, frames / 6);
  for (const char* scenario : {"same-scene", "driving"})
  {
    const bool driving = std::string(scenario) == "driving";
    projector->subProp("Frame")->setValue(driving ? "alloc_bench_driving" : "alloc_bench_fixed");
    int frame_index = 0;
    // Median process CPU per frame over one block, with or without D.
    auto blockMedian = [&](bool lens) {
      sensor_msgs::CameraInfo with = plain;
      if (lens)
      {
        with.D = { -0.2, 0.05, 0, 0, 0 };
      }
      info_pub.publish(with);
      const bool applied = waitFor(
          [&] {
            const rviz::StatusProperty* status = distortionStatus();
            return lens ? status && status->getLevel() == rviz::StatusProperty::Ok : status == nullptr;
          },
          5.0);
      std::vector<double> cpu;
      for (int i = 0; i < 30 + block; ++i)  // 30 frames to settle after the change
      {
        spin(0.0);
        if (driving)
        {
          drive(frame_index++);
        }
        else
        {
          rviz_projector::ProjectionChangeCounter::bump();
        }
        const double cpu0 = processCpuMs();
        render_now();
        if (i >= 30)
        {
          cpu.push_back(processCpuMs() - cpu0);
        }
      }
      return applied ? percentile(cpu, 0.5) : -1.0;
    };
    std::vector<double> extra;
    std::printf("# paired %s: warp's extra CPU ms per frame (median of %d frames with D - without), per pair:",
                scenario, block);
    for (int pair = 0; pair < 6; ++pair)
    {
      const double without = blockMedian(false);
      const double with = blockMedian(true);
      if (without < 0.0 || with < 0.0)
      {
        std::fprintf(stderr, "alloc_bench: the lens was not applied in time (paired %s)\n", scenario);
        return 1;
      }
      extra.push_back(with - without);
      std::printf(" %.2f", with - without);
    }
    std::printf("; median %.2f\n", percentile(extra, 0.5));
    std::fflush(stdout);
  }

  delete manager;
  delete panel;
  return 0;
}
