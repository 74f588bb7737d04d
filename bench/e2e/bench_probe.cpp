// rviz_projector_bench_probe: the measuring half of `scripts/bench --e2e`.
//
// Watches one output window's pixels on the X server (the rectangle the window occupies on the
// screen, read back with MIT-SHM) and drives the scene over ROS, for one pipeline at a time:
//
//   drive        robot driving (demo_navigation's plans relayed to the ProjectedPath topic):
//                frames/s delivered (content changes of the window) and CPU of every process
//   idle         robot stopped (demo_navigation SIGSTOPped), same plan: frames/s and CPU
//   latency      robot stopped: publish a changed path (in view of the projector), time until the
//                first changed pixel in the window; the path alternates between two variants
//                (--latency-poses poses, 100 by default)
//   latency100k  the same with a 100,000-pose path (about 10,000 arrows)
//   drive10k     robot driving with a 100,000-pose path of ~10,000 arrows laid over its circuit
//
// Frames are detected from the pixels, not from anyone's counters: the probe listens to XDamage
// on the root window (every drawing operation the server performs), and after each batch of
// damage touching the watched rectangle grabs that rectangle (XShmGetImage) and compares it with
// the previous grab; a frame counts when any pixel differs. The change time is the time the
// damage event arrived. --poll-ms N instead grabs every N ms (no XDamage needed, more CPU).
//
// Output: one line per measurement, tab separated: pipeline, phase, trial, metric, value. CPU is
// in cores (1.0 = one core busy) from /proc/<pid>/stat utime+stime over the trial. Memory: the
// resident set size (VmRSS of /proc/<pid>/status) of every process after the first frame (phase
// memory_start) and after the last phase (memory_end).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <dirent.h>
#include <poll.h>
#include <sys/ipc.h>
#include <sys/shm.h>
#include <unistd.h>

#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/extensions/XShm.h>
#include <X11/extensions/Xdamage.h>
#include <X11/extensions/Xfixes.h>

#include <nav_msgs/Path.h>
#include <ros/ros.h>

#include "x11_windows.h"

#include "probe_common.h"
#include "probe_cpu.h"
#include "probe_screen.h"

namespace
{
using namespace bench_probe;

// ---- options --------------------------------------------------------------------------------
struct Options
{
  std::string pipeline = "ours";
  std::string window;          // substring of the output window's title
  bool place_image = false;    // move the window so its image area lands at place_x, place_y
  int place_x = 0, place_y = 0;
  int image_width = 1280, image_height = 800;
  std::vector<std::pair<std::string, pid_t>> pids;  // processes whose CPU is measured
  pid_t demo_pid = 0;
  std::string path_topic = "/bench/path";
  std::string relay_from = "/demo/plan";
  std::vector<std::string> phases{"drive", "idle", "latency", "latency100k", "drive10k"};
  int trials = 20;
  int latency_trials = 25;
  int latency_poses = 100;
  double trial_seconds = 1.0;
  double warmup_seconds = 3.0;
  double poll_ms = 0.0;  // 0: XDamage-driven grabs
  std::string split_threads = "rviz";  // process whose CPU is also reported per thread group
  std::string out;
};

std::vector<std::string> split(const std::string& s, char sep)
{
  std::vector<std::string> parts;
  std::stringstream in(s);
  std::string part;
  while (std::getline(in, part, sep))
  {
    if (!part.empty())
    {
      parts.push_back(part);
    }
  }
  return parts;
}

Options parseOptions(int argc, char** argv)
{
  Options o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc)
      {
        fail("missing value for " + a);
      }
      return argv[++i];
    };
    if (a == "--pipeline") o.pipeline = value();
    else if (a == "--window") o.window = value();
    else if (a == "--place-image")
    {
      const auto xy = split(value(), ',');
      if (xy.size() != 2) fail("--place-image X,Y");
      o.place_image = true;
      o.place_x = std::stoi(xy[0]);
      o.place_y = std::stoi(xy[1]);
    }
    else if (a == "--image-size")
    {
      const auto wh = split(value(), 'x');
      if (wh.size() != 2) fail("--image-size WxH");
      o.image_width = std::stoi(wh[0]);
      o.image_height = std::stoi(wh[1]);
    }
    else if (a == "--pid")
    {
      const std::string v = value();
      const auto eq = v.find('=');
      if (eq == std::string::npos) fail("--pid NAME=PID");
      o.pids.emplace_back(v.substr(0, eq), static_cast<pid_t>(std::stol(v.substr(eq + 1))));
    }
    else if (a == "--demo-pid") o.demo_pid = static_cast<pid_t>(std::stol(value()));
    else if (a == "--path-topic") o.path_topic = value();
    else if (a == "--relay-from") o.relay_from = value();
    else if (a == "--phases") o.phases = split(value(), ',');
    else if (a == "--trials") o.trials = std::stoi(value());
    else if (a == "--latency-trials") o.latency_trials = std::stoi(value());
    else if (a == "--latency-poses") o.latency_poses = std::stoi(value());
    else if (a == "--trial-seconds") o.trial_seconds = std::stod(value());
    else if (a == "--warmup-seconds") o.warmup_seconds = std::stod(value());
    else if (a == "--poll-ms") o.poll_ms = std::stod(value());
    else if (a == "--out") o.out = value();
    else if (a == "--threads") o.split_threads = value();
    else if (a.rfind("__", 0) == 0 || a.find(":=") != std::string::npos) continue;  // ROS remaps
    else fail("unknown option " + a);
  }
  if (o.window.empty()) fail("--window TITLE is required");
  if (o.latency_poses < 2) fail("--latency-poses N: at least 2");
  return o;
}

// ---- paths -----------------------------------------------------------------------------------
constexpr double kPoseStep = 0.025;

geometry_msgs::PoseStamped pose(const std_msgs::Header& header, double x, double y)
{
  geometry_msgs::PoseStamped p;
  p.header = header;
  p.pose.position.x = x;
  p.pose.position.y = y;
  p.pose.orientation.w = 1.0;
  return p;
}

/**
 * A straight path in base_link ending in the projector's lit area (base_link x 0.65 .. 2.0 m for
 * the demo's mount): variant 0 at y = +0.25, variant 1 at y = -0.25. Long paths start far behind
 * the robot; only their last ~1.1 m is in view. Stamp 0: drawn with the latest tf, also while the
 * demo node is stopped.
 */
nav_msgs::Path straightPath(std::size_t poses, int variant)
{
  nav_msgs::Path path;
  path.header.frame_id = "base_link";
  path.header.stamp = ros::Time(0);
  path.poses.reserve(poses);
  const double y = variant == 0 ? 0.25 : -0.25;
  const double end_x = 1.8;
  for (std::size_t i = 0; i < poses; ++i)
  {
    path.poses.push_back(pose(path.header, end_x - kPoseStep * static_cast<double>(poses - 1 - i), y));
  }
  return path;
}

/**
 * A planner's plan over a large hall: back and forth along x between x = -8 and 12 m, the lines
 * 0.15 m apart from y = -8.5 m on (map frame), until `poses` poses. With Exact spacing 0.25 m a
 * 100,000-pose path makes ~10,000 arrows that do not overlap; the demo robot drives over the part
 * around (0..4, 0..2.5), so a few dozen of them are in the projector's view at any time while the
 * renderer is handed all of them.
 */
nav_msgs::Path hallPath(std::size_t poses)
{
  nav_msgs::Path path;
  path.header.frame_id = "map";
  path.header.stamp = ros::Time(0);
  path.poses.reserve(poses);
  const double x0 = -8.0, x1 = 12.0, pitch = 0.15;
  const int per_line = static_cast<int>((x1 - x0) / kPoseStep);
  for (int line = 0; path.poses.size() < poses; ++line)
  {
    const double y = -8.5 + pitch * line;
    for (int s = 0; s < per_line && path.poses.size() < poses; ++s)
    {
      const double along = kPoseStep * s;
      path.poses.push_back(pose(path.header, line % 2 == 0 ? x0 + along : x1 - along, y));
    }
  }
  return path;
}

// ---- the bench ---------------------------------------------------------------------------
class Bench
{
public:
  explicit Bench(const Options& options)
    : o_(options), screen_(options.poll_ms), cpu_(options.pids, options.split_threads), rng_(12345u)
  {
    if (!o_.out.empty())
    {
      out_.open(o_.out, std::ios::app);
      if (!out_) fail("cannot write " + o_.out);
    }
    publisher_ = nh_.advertise<nav_msgs::Path>(o_.path_topic, 1);
    relay_ = nh_.subscribe<nav_msgs::Path>(o_.relay_from, 1, [this](const nav_msgs::Path::ConstPtr& msg) {
      if (relaying_)
      {
        publisher_.publish(msg);
      }
    });
  }

  void run()
  {
    findWindow();
    waitForSubscriber();
    relaying_ = true;
    note("waiting for the first frame");
    if (!waitForChange(Clock::now() + std::chrono::seconds(60)))
    {
      fail("the window never changed: is the scene moving?");
    }
    emitMemory("memory_start");
    emit("setup", 0, "latency_poses", o_.latency_poses);
    for (const std::string& phase : o_.phases)
    {
      if (phase == "drive") drive("drive");
      else if (phase == "idle") idle();
      else if (phase == "latency") latency("latency", static_cast<std::size_t>(o_.latency_poses));
      else if (phase == "latency100k") latency("latency100k", 100000);
      else if (phase == "drive10k") drive10k();
      else fail("unknown phase " + phase);
    }
    resumeDemo();
    emitMemory("memory_end");
    if (o_.place_image)
    {
      checkOnTop();
    }
  }

private:
  void emit(const std::string& phase, int trial, const std::string& metric, double value)
  {
    char line[512];
    std::snprintf(line, sizeof line, "%s\t%s\t%d\t%s\t%.6g\n", o_.pipeline.c_str(), phase.c_str(), trial,
                  metric.c_str(), value);
    if (out_.is_open())
    {
      out_ << line << std::flush;
    }
    else
    {
      std::fputs(line, stdout);
    }
  }

  void emitMemory(const std::string& phase)
  {
    for (const auto& p : cpu_.pids())
    {
      if (p.first != "probe")
      {
        emit(phase, 0, "rss_mb." + p.first, rssMegabytes(p.second));
      }
    }
  }

  void findWindow()
  {
    note("looking for a window titled '" + o_.window + "'");
    const auto deadline = Clock::now() + std::chrono::seconds(90);
    while ((window_ = screen_.findWindow(o_.window)) == 0)
    {
      if (Clock::now() > deadline) fail("no viewable window titled '" + o_.window + "'");
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    Rect rect = screen_.windowRect(window_);
    if (o_.place_image)
    {
      rect = placeImage(rect);
    }
    rect = screen_.clipToScreen(rect);
    char text[160];
    std::snprintf(text, sizeof text, "watching %dx%d at %d,%d (window 0x%lx)", rect.width, rect.height, rect.x, rect.y,
                  window_);
    note(text);
    emit("setup", 0, "watched_width", rect.width);
    emit("setup", 0, "watched_height", rect.height);
    emit("setup", 0, "watched_x", rect.x);
    emit("setup", 0, "watched_y", rect.y);
    if (rect.width <= 0 || rect.height <= 0) fail("the window is off screen");
    screen_.watch(rect);
  }

  /**
   * image_view's window holds a toolbar and a status bar around the image. The projector image is
   * mostly black (nothing but arrows on a black background), the bars are not: the image is the
   * bounding box of the rows and columns that are mostly black. Moves the window so the image lands
   * at place_x, place_y (the projector screen) and raises it; returns the image's rectangle.
   */
  Rect placeImage(const Rect& window_rect)
  {
    Display* d = screen_.display();
    // Wait for the first image (the window is grey until then).
    Rect image{};
    const auto deadline = Clock::now() + std::chrono::seconds(60);
    while (Clock::now() < deadline)
    {
      const Rect on_screen = screen_.clipToScreen(screen_.windowRect(window_));
      if (on_screen.width > 0 && on_screen.height > 0 && findDarkBox(on_screen, image))
      {
        break;
      }
      image = Rect{};
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
    }
    const Rect now_rect = screen_.windowRect(window_);
    if (image.width == 0)
    {
      note("could not find the image inside the window: watching the whole window");
      XMoveWindow(d, window_, o_.place_x, o_.place_y);
      XRaiseWindow(d, window_);
      XSync(d, False);
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
      return screen_.windowRect(window_);
    }
    const int dx = image.x - now_rect.x, dy = image.y - now_rect.y;
    char text[200];
    std::snprintf(text, sizeof text, "image %dx%d at +%d+%d inside the %dx%d window", image.width, image.height, dx, dy,
                  window_rect.width, window_rect.height);
    note(text);
    XMoveWindow(d, window_, o_.place_x - dx, o_.place_y - dy);
    XRaiseWindow(d, window_);
    XSync(d, False);
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    const Rect moved = screen_.windowRect(window_);
    return Rect{moved.x + dx, moved.y + dy, image.width, image.height};
  }

  bool findDarkBox(const Rect& rect, Rect& box)
  {
    const std::vector<std::uint32_t> px = screen_.snapshot(rect);
    auto dark = [](std::uint32_t p) { return (p & 0xF0F0F0u) == 0; };
    int top = -1, bottom = -1, left = -1, right = -1;
    for (int y = 0; y < rect.height; ++y)
    {
      int n = 0;
      for (int x = 0; x < rect.width; ++x) n += dark(px[static_cast<std::size_t>(y) * rect.width + x]);
      if (n * 2 > rect.width)
      {
        if (top < 0) top = y;
        bottom = y;
      }
    }
    if (top < 0) return false;
    for (int x = 0; x < rect.width; ++x)
    {
      int n = 0;
      for (int y = top; y <= bottom; ++y) n += dark(px[static_cast<std::size_t>(y) * rect.width + x]);
      if (n * 2 > bottom - top + 1)
      {
        if (left < 0) left = x;
        right = x;
      }
    }
    box = Rect{rect.x + left, rect.y + top, right - left + 1, bottom - top + 1};
    // Expect the image's size; allow a few rows/columns lost to a frame or the screen edge.
    return std::abs(box.width - o_.image_width) <= 8 && box.height >= o_.image_height / 2;
  }

  void checkOnTop()
  {
    // Nothing may cover the watched image at the end (e.g. the projector window raising itself).
    Window root_return, parent;
    Window* children = nullptr;
    unsigned count = 0;
    XQueryTree(screen_.display(), DefaultRootWindow(screen_.display()), &root_return, &parent, &children, &count);
    bool top = count > 0 && children[count - 1] == window_;
    for (unsigned i = 0; i < count && !top; ++i)
    {
      // Windows mapped above ours that are not viewable do not count.
      if (children[i] == window_)
      {
        top = true;
        for (unsigned j = i + 1; j < count; ++j)
        {
          XWindowAttributes a;
          if (XGetWindowAttributes(screen_.display(), children[j], &a) && a.map_state == IsViewable) top = false;
        }
      }
    }
    if (children) XFree(children);
    emit("setup", 0, "window_on_top_at_end", top ? 1 : 0);
  }

  void waitForSubscriber()
  {
    const auto deadline = Clock::now() + std::chrono::seconds(60);
    while (publisher_.getNumSubscribers() == 0)
    {
      if (Clock::now() > deadline) fail("nobody subscribes to " + o_.path_topic);
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }

  bool waitForChange(Clock::time_point deadline, Clock::time_point* when = nullptr)
  {
    WatchedScreen::Event e;
    while (screen_.next(deadline, e))
    {
      if (e.changed)
      {
        if (when) *when = e.time;
        return true;
      }
    }
    return false;
  }

  /// Waits until no pixel changed for `quiet` (at most `limit`); false if it never settled.
  bool waitQuiet(double quiet, double limit)
  {
    const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limit));
    while (Clock::now() < end)
    {
      const auto until = std::min(end, Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(quiet)));
      if (!waitForChange(until))
      {
        return Clock::now() >= until;
      }
    }
    return false;
  }

  void sleepWatching(double s)
  {
    const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
    WatchedScreen::Event e;
    while (screen_.next(end, e))
    {
    }
  }

  /// One timed window: content changes and draws per second, and CPU per process.
  void measure(const std::string& phase, int trial)
  {
    const long draws_before = screen_.draws();
    cpu_.start();
    const auto start = Clock::now();
    const auto end = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(o_.trial_seconds));
    long changes = 0;
    WatchedScreen::Event e;
    while (screen_.next(end, e))
    {
      changes += e.changed ? 1 : 0;
    }
    const double wall = seconds(Clock::now() - start);
    const auto usage = cpu_.stop();
    emit(phase, trial, "fps", changes / wall);
    emit(phase, trial, "draws_per_s", (screen_.draws() - draws_before) / wall);
    // total: the pipeline's processes; others: whatever else kept the machine busy meanwhile
    // (system-wide busy time minus every measured process, the probe included); steal: time the
    // hypervisor did not give to this virtual machine at all.
    double total = 0.0, measured = 0.0, system = 0.0;
    for (const auto& u : usage)
    {
      if (u.first == "system")
      {
        system = u.second;
        continue;
      }
      if (u.first == "steal")
      {
        emit(phase, trial, "cpu.steal", u.second);
        continue;
      }
      if (u.first.rfind("thread:", 0) == 0)
      {
        emit(phase, trial, "cpu." + u.first.substr(7), u.second);  // part of its process's figure
        continue;
      }
      emit(phase, trial, "cpu." + u.first, u.second);
      if (std::isfinite(u.second))
      {
        measured += u.second;
        total += u.first == "probe" ? 0.0 : u.second;
      }
    }
    emit(phase, trial, "cpu.total", total);
    emit(phase, trial, "cpu.others", std::max(0.0, system - measured));
  }

  void drive(const std::string& phase)
  {
    resumeDemo();
    relaying_ = true;
    note(phase + ": robot driving, warming up");
    sleepWatching(o_.warmup_seconds);
    for (int t = 0; t < o_.trials; ++t)
    {
      measure(phase, t);
    }
    note(phase + ": done");
  }

  void idle()
  {
    // Keep the demo's plan: wait for it to replan once more through the relay, then stop it.
    relaying_ = true;
    resumeDemo();
    sleepWatching(1.2);
    pauseDemo();
    note("idle: robot stopped, settling");
    waitQuiet(1.0, 5.0);
    for (int t = 0; t < o_.trials; ++t)
    {
      measure("idle", t);
    }
    note("idle: done");
  }

  void latency(const std::string& phase, std::size_t poses)
  {
    pauseDemo();
    relaying_ = false;
    const nav_msgs::Path paths[2] = {straightPath(poses, 0), straightPath(poses, 1)};
    note(phase + ": " + std::to_string(poses) + "-pose paths");
    // Put variant 1 up first, so that every trial changes the drawing.
    publisher_.publish(paths[1]);
    waitQuiet(0.5, 5.0);
    std::uniform_real_distribution<double> jitter(0.0, 0.05);
    int timeouts = 0;
    for (int t = 0; t < o_.latency_trials; ++t)
    {
      if (!waitQuiet(0.3, 5.0))
      {
        note(phase + ": the window does not settle; measuring anyway");
      }
      // A random phase against rviz's and the projector's timers.
      std::this_thread::sleep_for(std::chrono::duration<double>(jitter(rng_)));
      const auto start = Clock::now();
      publisher_.publish(paths[t % 2]);
      Clock::time_point seen;
      if (waitForChange(start + std::chrono::seconds(5), &seen))
      {
        emit(phase, t, "latency_ms", 1000.0 * seconds(seen - start));
      }
      else
      {
        ++timeouts;
        emit(phase, t, "latency_timeout", 1);
      }
    }
    note(phase + ": done" + (timeouts ? " (" + std::to_string(timeouts) + " timeouts)" : std::string()));
  }

  void drive10k()
  {
    relaying_ = false;
    const nav_msgs::Path path = hallPath(100000);
    publisher_.publish(path);
    resumeDemo();
    note("drive10k: robot driving over a 100,000-pose plan (~10,000 arrows), warming up");
    sleepWatching(o_.warmup_seconds);
    for (int t = 0; t < o_.trials; ++t)
    {
      measure("drive10k", t);
    }
    note("drive10k: done");
  }

  void pauseDemo()
  {
    if (o_.demo_pid > 0 && kill(o_.demo_pid, SIGSTOP) != 0) fail("cannot stop the demo node");
  }
  void resumeDemo()
  {
    if (o_.demo_pid > 0) kill(o_.demo_pid, SIGCONT);
  }

  Options o_;
  WatchedScreen screen_;
  CpuMeter cpu_;
  std::mt19937 rng_;
  std::ofstream out_;
  Window window_ = 0;
  ros::NodeHandle nh_;
  ros::Publisher publisher_;
  ros::Subscriber relay_;
  std::atomic<bool> relaying_{false};
};
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "rviz_projector_bench_probe", ros::init_options::AnonymousName);
  const Options options = parseOptions(argc, argv);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  {
    Bench bench(options);
    bench.run();
  }
  spinner.stop();
  return 0;
}
