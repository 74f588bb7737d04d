# Build time only (CI's 25-minute budget): precompiled third-party headers. Included LAST from
# CMakeLists.txt, once every target exists; it adds no target and changes no flag of its own (but
# one: the users of test_core's header get its -O1 in the sanitizer build, see below).
#
# Parsing rviz, OGRE, Qt and ROS headers is most of the cost of each of our translation units.
# A few precompiled headers, each built once per workspace, are shared by the targets:
#   projector_host        rviz/OGRE/Qt/ROS: every executable or static library that links the
#                         plugin library or the rviz test support (projector_host, rviz tests,
#                         benches). The plugin library ${PROJECT_NAME} precompiles the same
#                         headers for itself: gcc refuses to share across its -D..._EXPORTS.
#   projector_info_publisher  roscpp and messages: every executable that links the ROS
#                         conversions but not the plugin (nodes, node tests).
#   test_core             gtest and the standard library: the core's tests.
# An owner is an executable of `all` (or a test for tests): the flags of its users must match
# (gcc: -fPIC of a library vs -fpie of an executable, macros defined at precompilation).
# Targets pick theirs by what they link (below), so a new test gets a shared header without a
# line here. The ROS-free core itself gets none: its sources must keep compiling without ROS.
#
# Safe by construction: only third-party headers (found through SYSTEM include directories, so
# -Werror still concerns our code only), none of which depend on a macro our sources define.
# A translation unit sees the same declarations (it includes these headers itself or not at all:
# nothing of ours overloads on their absence). gcc rejects a precompiled header built with other
# flags; CMake adds -Winvalid-pch, which -Werror makes a build error, never a silent fallback.
# The sanitizer build has its flags on every target (add_compile_options), so it shares them too.
# Off: -DCMAKE_DISABLE_PRECOMPILE_HEADERS=ON (CMake's own switch).
# target_precompile_headers needs CMake 3.16 (Debian 12: 3.25, Ubuntu 20.04: 3.16); an older CMake
# builds without (the return below), hence catkin_lint's cmake_old ignored at each call.
if(NOT COMMAND target_precompile_headers)
  return()
endif()

set(${PROJECT_NAME}_PCH_STD <algorithm> <array> <chrono> <cmath> <cstdint> <functional> <limits> <map>
  <memory> <string> <vector>)
set(${PROJECT_NAME}_PCH_ROS ${${PROJECT_NAME}_PCH_STD} <ros/ros.h> <geometry_msgs/TransformStamped.h>
  <nav_msgs/Path.h> <sensor_msgs/CameraInfo.h> <tf2/LinearMath/Transform.h> <tf2_ros/buffer.h>)
set(${PROJECT_NAME}_PCH_RVIZ ${${PROJECT_NAME}_PCH_ROS}
  <QApplication> <QObject> <QScreen> <QString> <QTimer> <QWidget> <QWindow>
  <OgreCamera.h> <OgreMaterialManager.h> <OgreRenderWindow.h> <OgreRoot.h> <OgreSceneManager.h>
  <OgreSceneNode.h>
  <rviz/config.h> <rviz/display.h> <rviz/display_context.h> <rviz/display_group.h>
  <rviz/properties/color_property.h> <rviz/properties/enum_property.h> <rviz/properties/float_property.h>
  <rviz/properties/ros_topic_property.h> <rviz/visualization_manager.h>)

#catkin_lint: ignore_once cmake_old
target_precompile_headers(${PROJECT_NAME} PRIVATE ${${PROJECT_NAME}_PCH_RVIZ})
if(TARGET projector_host)
  #catkin_lint: ignore_once cmake_old
  target_precompile_headers(projector_host PRIVATE ${${PROJECT_NAME}_PCH_RVIZ})
endif()
if(TARGET projector_info_publisher)
  #catkin_lint: ignore_once cmake_old
  target_precompile_headers(projector_info_publisher PRIVATE ${${PROJECT_NAME}_PCH_ROS})
endif()
if(TARGET test_core)
  #catkin_lint: ignore_once cmake_old
  target_precompile_headers(test_core PRIVATE ${${PROJECT_NAME}_PCH_STD} <gtest/gtest.h>)
endif()

# Every other target of this directory reuses the header of the heaviest library it links.
get_property(${PROJECT_NAME}_pch_targets DIRECTORY PROPERTY BUILDSYSTEM_TARGETS)
foreach(target ${${PROJECT_NAME}_pch_targets})
  get_target_property(type ${target} TYPE)
  get_target_property(links ${target} LINK_LIBRARIES)
  # Not a shared library: gcc refuses a header precompiled without its -D..._EXPORTS.
  if(NOT type MATCHES "^(EXECUTABLE|STATIC_LIBRARY)$" OR NOT links)
    continue()
  endif()
  set(from "")
  foreach(candidate ${PROJECT_NAME}_rviz_test_support:projector_host ${PROJECT_NAME}:projector_host
                    ${PROJECT_NAME}_ros:projector_info_publisher)
    string(REPLACE ":" ";" candidate ${candidate})
    list(GET candidate 0 linked)
    list(GET candidate 1 owner)
    list(FIND links ${linked} found)
    if(NOT found EQUAL -1 AND TARGET ${owner})
      set(from ${owner})
      break()
    endif()
  endforeach()
  if(from STREQUAL "" AND TARGET test_core AND target MATCHES "^test_")
    # The core's other tests (never a target of `all`: reusing makes it depend on test_core).
    list(FIND links ${PROJECT_NAME}_core found)
    if(NOT found EQUAL -1)
      set(from test_core)
      # The one flag this file sets: the sanitizer build compiles test_core at -O1 (CMakeLists.txt),
      # and gcc refuses its header in a unit compiled otherwise ("__OPTIMIZE__ not defined").
      target_compile_options(${target} PRIVATE ${${PROJECT_NAME}_SANITIZE_OPTIMIZE})
    endif()
  endif()
  get_target_property(own ${target} PRECOMPILE_HEADERS)
  if(NOT from STREQUAL "" AND NOT own AND NOT from STREQUAL target)
    #catkin_lint: ignore_once cmake_old
    target_precompile_headers(${target} REUSE_FROM ${from})
  endif()
endforeach()
