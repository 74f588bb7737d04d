# Benchmarks: built with the package, run by scripts/bench (never by the tests).
#  - rviz_projector_microbench: Google Benchmark microbenchmarks of the core and of the
#    ProjectedPath CPU update, each next to a re-implementation of the reference pipeline, and of
#    the mount calibration's solver.
#  - rviz_projector_bench_probe: the end-to-end bench's X11 probe and ROS driver (scripts/bench --e2e).
#  - rviz_projector_slip_probe: the motion slip bench's synthetic robot and one-row X11 probe
#    (scripts/bench --slip).
#  - rviz_projector_allocbench: heap allocations per projector frame and RSS, in a real rviz with a
#    ProjectorCamera (scripts/bench --alloc; needs an X server and a ROS master).
# Each is skipped, with a message, when its libraries are missing. Only the microbenchmarks are
# part of the default build (scripts/test smoke-runs them); the probes and the allocation bench are
# EXCLUDE_FROM_ALL: scripts/bench builds them by name (CI time: 7 translation units fewer).

find_package(benchmark QUIET)
if(benchmark_FOUND)
  #catkin_lint: ignore uninstalled_target
  add_executable(${PROJECT_NAME}_microbench
    bench/micro/acknowledge_benchmarks.cpp
    bench/micro/bench_paths.cpp
    bench/micro/calibration_benchmarks.cpp
    bench/micro/corridor_benchmarks.cpp
    bench/micro/cue_benchmarks.cpp
    bench/micro/mask_benchmarks.cpp
    bench/micro/mesh_benchmarks.cpp
    bench/micro/micro_benchmarks.cpp
    bench/micro/off_view_benchmarks.cpp
    bench/micro/reference_baseline.cpp
    bench/micro/warp_benchmarks.cpp
  )
  set_target_properties(${PROJECT_NAME}_microbench PROPERTIES AUTOMOC OFF)
  target_include_directories(${PROJECT_NAME}_microbench PRIVATE bench/micro test/support)
  # pathToFloorPoints is in the ROS conversion library, FloorMesh in the rviz plugin library.
  target_link_libraries(${PROJECT_NAME}_microbench ${PROJECT_NAME} ${PROJECT_NAME}_ros ${PROJECT_NAME}_core
    ${catkin_LIBRARIES} benchmark::benchmark)
  target_compile_options(${PROJECT_NAME}_microbench PRIVATE ${${PROJECT_NAME}_WARNINGS})
  add_dependencies(${PROJECT_NAME}_microbench ${catkin_EXPORTED_TARGETS})
else()
  message(STATUS "${PROJECT_NAME}: Google Benchmark not found (apt-get install libbenchmark-dev): microbenchmarks skipped")
endif()

#catkin_lint: ignore uninstalled_target
add_executable(${PROJECT_NAME}_allocbench EXCLUDE_FROM_ALL bench/alloc/alloc_bench.cpp)
set_target_properties(${PROJECT_NAME}_allocbench PROPERTIES AUTOMOC OFF)
target_link_libraries(${PROJECT_NAME}_allocbench ${PROJECT_NAME} ${catkin_LIBRARIES} Qt5::Widgets)
target_compile_options(${PROJECT_NAME}_allocbench PRIVATE ${${PROJECT_NAME}_WARNINGS})
add_dependencies(${PROJECT_NAME}_allocbench ${catkin_EXPORTED_TARGETS})

# X11 (with its XShm, Xdamage, Xfixes parts) is found in CMakeLists.txt.
if(X11_FOUND AND X11_XShm_FOUND AND X11_Xdamage_FOUND AND X11_Xfixes_FOUND)
  #catkin_lint: ignore uninstalled_target
  add_executable(${PROJECT_NAME}_bench_probe EXCLUDE_FROM_ALL bench/e2e/bench_probe.cpp bench/e2e/probe_common.h bench/e2e/probe_cpu.h
                                        bench/e2e/probe_screen.h bench/e2e/x11_windows.cpp)
  set_target_properties(${PROJECT_NAME}_bench_probe PROPERTIES AUTOMOC OFF)
  target_include_directories(${PROJECT_NAME}_bench_probe SYSTEM PRIVATE ${X11_INCLUDE_DIR})
  target_link_libraries(${PROJECT_NAME}_bench_probe ${catkin_LIBRARIES} ${X11_LIBRARIES} ${X11_Xext_LIB}
    ${X11_Xdamage_LIB} ${X11_Xfixes_LIB})
  target_compile_options(${PROJECT_NAME}_bench_probe PRIVATE ${${PROJECT_NAME}_WARNINGS})
  add_dependencies(${PROJECT_NAME}_bench_probe ${catkin_EXPORTED_TARGETS})
  # The motion slip bench (scripts/bench --slip): synthetic robot + one-row probe (issue 14).
  #catkin_lint: ignore uninstalled_target
  add_executable(${PROJECT_NAME}_slip_probe EXCLUDE_FROM_ALL bench/e2e/slip_geometry.cpp bench/e2e/slip_probe.cpp bench/e2e/slip_x11.cpp
    bench/e2e/x11_windows.cpp)
  set_target_properties(${PROJECT_NAME}_slip_probe PROPERTIES AUTOMOC OFF)
  target_include_directories(${PROJECT_NAME}_slip_probe SYSTEM PRIVATE ${X11_INCLUDE_DIR})
  target_link_libraries(${PROJECT_NAME}_slip_probe ${catkin_LIBRARIES} ${X11_LIBRARIES} ${X11_Xext_LIB})
  target_compile_options(${PROJECT_NAME}_slip_probe PRIVATE ${${PROJECT_NAME}_WARNINGS})
  add_dependencies(${PROJECT_NAME}_slip_probe ${catkin_EXPORTED_TARGETS})
else()
  message(STATUS "${PROJECT_NAME}: X11 with MIT-SHM, XDamage and XFixes not found (apt-get install libx11-dev libxext-dev libxdamage-dev libxfixes-dev): e2e bench probe skipped")
endif()
