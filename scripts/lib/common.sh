# shellcheck shell=bash
# Shared by scripts/demo, scripts/test and scripts/bench: system packages, catkin workspace, build.
# Source it; it expects `set -euo pipefail` in the caller.

RP_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
# Workspaces live OUTSIDE the repository: the repository is linked into the workspace's src/, and a
# workspace inside the repository made a link loop (rosrun searches the package folder following
# links: "find: File system loop detected"). One folder per clone, named after it:
#   ${XDG_CACHE_HOME:-~/.cache}/rviz_projector/<clone folder name>-<hash of its path>/{ws,ws-sanitize,ws-bench}
RP_WS_BASE="${RP_WS_BASE:-${XDG_CACHE_HOME:-$HOME/.cache}/rviz_projector/$(basename "$RP_ROOT")-$(printf '%s' "$RP_ROOT" | md5sum | cut -c1-8)}"
RP_WS="${RP_WS:-$RP_WS_BASE/ws}"
# A pyenv (or other) python3 first on PATH lacks catkin_pkg: ROS tools must run with the system one.
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:$PATH"

rp_log() { printf '\033[1m[rviz_projector]\033[0m %s\n' "$*" >&2; }

# Debian 12 packages ROS 1 in /usr; Ubuntu 20.04 gets it from packages.ros.org as ros-noetic-*.
rp_is_noetic_ubuntu() { [ -f /opt/ros/noetic/setup.bash ] || grep -q 'VERSION_CODENAME=focal' /etc/os-release 2>/dev/null; }

rp_packages() {
  local common="build-essential cmake xvfb xauth x11-utils x11-xserver-utils x11-apps imagemagick
    libgl1-mesa-dri mesa-utils xserver-xorg-core xserver-xorg-video-dummy libgtest-dev googletest
    libbenchmark-dev qtbase5-dev libx11-dev libgl-dev libxext-dev libxdamage-dev libxfixes-dev
    libyaml-cpp-dev xdotool python3-xlib desktop-file-utils lld libpolyclipping-dev pkg-config"
  if rp_is_noetic_ubuntu; then
    echo "$common python3-catkin-pkg ros-noetic-catkin ros-noetic-roscpp ros-noetic-rviz ros-noetic-pluginlib
      ros-noetic-nav-msgs ros-noetic-sensor-msgs ros-noetic-geometry-msgs ros-noetic-visualization-msgs
      ros-noetic-std-msgs ros-noetic-tf2 ros-noetic-tf2-ros ros-noetic-tf2-geometry-msgs ros-noetic-rostest
      ros-noetic-roslaunch ros-noetic-rosbash ros-noetic-rosservice ros-noetic-image-view ros-noetic-rostopic ros-noetic-camera-calibration-parsers ros-noetic-image-geometry
      ros-noetic-roslib ros-noetic-diagnostic-updater ros-noetic-diagnostic-msgs ros-noetic-std-srvs ros-noetic-actionlib-msgs ros-noetic-cv-bridge ros-noetic-rosgraph-msgs libopencv-contrib-dev"
  else
    echo "$common catkin python3-catkin-pkg python3-rospkg python3-empy ros-message-generation
      libroscpp-dev librviz-dev rviz pluginlib-dev libnav-msgs-dev libsensor-msgs-dev libgeometry-msgs-dev
      libvisualization-msgs-dev libstd-msgs-dev libtf2-dev libtf2-ros-dev libtf2-geometry-msgs-dev
      librostest-dev python3-rostest python3-roslaunch python3-rosmaster python3-rosnode python3-rostopic python3-rosservice
      rosbash libimage-view-dev libnodeletlib-tools ros-image-view catkin-lint libcamera-calibration-parsers-dev
      tf2-tools clang libclang-rt-14-dev libimage-geometry-dev libopencv-dev libopencv-contrib-dev python3-nav-msgs python3-sensor-msgs python3-rviz python3-visualization-msgs
      libdiagnostic-updater-dev libdiagnostic-msgs-dev python3-diagnostic-msgs libstd-srvs-dev python3-std-srvs
      libactionlib-msgs-dev libcv-bridge-dev python3-tf2-ros libros-rosgraph-msgs-dev"
  fi
}

# Installs whatever is missing, by explicit name (rosdep has no index here).
rp_install_deps() {
  local missing=()
  local p
  for p in $(rp_packages); do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  rp_log "installing ${#missing[@]} system packages: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}"
}

rp_source_ros() {
  if [ -f /opt/ros/noetic/setup.bash ]; then
    set +u
    # shellcheck disable=SC1091
    source /opt/ros/noetic/setup.bash
    set -u
  fi
}

# Links the repository into $RP_WS/src/rviz_projector: a link pointing elsewhere (another clone, a
# moved repository) is replaced; anything that is not a link is left alone and is an error.
rp_link_source() {
  local link="$RP_WS/src/rviz_projector"
  mkdir -p "$RP_WS/src"
  case "$RP_WS/" in
    "$RP_ROOT"/*) rp_log "WARNING: workspace $RP_WS is inside the repository: rosrun will report file system loops" ;;
  esac
  if [ -L "$link" ]; then
    [ "$(readlink -f "$link")" = "$(readlink -f "$RP_ROOT")" ] && return 0
    rp_log "replacing stale link $link -> $(readlink "$link")"
    rm -f "$link"
  elif [ -e "$link" ]; then
    rp_log "$link exists and is not a link to $RP_ROOT: move it away"
    return 1
  fi
  ln -s "$RP_ROOT" "$link"
  # Workspaces of older versions of these scripts lived in the repository (.ws*/src/rviz_projector
  # linking back to it): drop those links, which make rosrun report file system loops.
  local old
  for old in "$RP_ROOT"/.ws*/src/rviz_projector; do
    if [ -L "$old" ] && [ "$(readlink -f "$old")" = "$(readlink -f "$RP_ROOT")" ]; then
      rp_log "removing $old (old in-repository workspace; it made a link loop)"
      rm -f "$old"
    fi
  done
}

# Builds the package in $RP_WS (the repository linked in as src/rviz_projector). Extra arguments
# go to CMake (e.g. -DRVIZ_PROJECTOR_SANITIZE=ON). Quick when nothing changed.
rp_build() {
  rp_source_ros
  rp_link_source
  rp_log "building in $RP_WS"
  # Build time (CI's budget): line tables only (-g1: file:line in backtraces and sanitizer
  # reports, no type information, much less to compile and link) and LLVM's lld linker when it is
  # installed (rp_packages lists it); many test executables link rviz, OGRE and Qt. RP_DEBUG_INFO=-g
  # gives full debug information for gdb.
  local speed=(-DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 ${RP_DEBUG_INFO:--g1} -DNDEBUG"
               -DCMAKE_CXX_FLAGS_DEBUG="${RP_DEBUG_INFO:--g1}")
  if command -v ld.lld >/dev/null 2>&1; then
    speed+=(-DCMAKE_EXE_LINKER_FLAGS=-fuse-ld=lld -DCMAKE_SHARED_LINKER_FLAGS=-fuse-ld=lld
            -DCMAKE_MODULE_LINKER_FLAGS=-fuse-ld=lld)
  fi
  (cd "$RP_WS" && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCATKIN_ENABLE_TESTING=ON "${speed[@]}" "$@" -j"$(nproc)" >"$RP_WS/build.log" 2>&1) || {
    tail -n 60 "$RP_WS/build.log" >&2
    rp_log "build failed (full log: $RP_WS/build.log)"
    return 1
  }
  set +u
  # shellcheck disable=SC1091
  source "$RP_WS/devel/setup.bash"
  set -u
}

# A free TCP port for a private ROS master.
rp_free_port() {
  /usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1]); s.close()'
}
