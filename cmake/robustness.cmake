# Robustness work (issue 4): bad-input matrix rostests and crash regressions of the core.
#
# The libFuzzer targets are NOT built here: libFuzzer needs clang while this package builds with
# the system compiler (g++ on Debian). They live in a small CMake project of their own, fuzz/,
# that scripts/test configures with clang++ (when available) and runs for a bounded time.
if(CATKIN_ENABLE_TESTING)
  # Regressions found by the fuzz targets (tests named DISABLED_ pin reported, unfixed bugs).
  catkin_add_gtest(test_core_regression
    test/core/core_regression_test.cpp
    test/core/core_test_main.cpp
  )
  target_link_libraries(test_core_regression ${PROJECT_NAME}_core)
  target_compile_options(test_core_regression PRIVATE ${${PROJECT_NAME}_WARNINGS})

  # The bad-input matrix in a real rviz: one executable, one rostest per part of the matrix (each
  # its own process and time limit, so a crash in one part does not hide the others).
  catkin_add_executable_with_gtest(test_robustness EXCLUDE_FROM_ALL
    test/rviz/robustness_camera_test.cpp
    test/rviz/robustness_config_test.cpp
    test/rviz/robustness_fixtures.h
    test/rviz/robustness_lifecycle_test.cpp
    test/rviz/robustness_path_test.cpp
  )
  target_link_libraries(test_robustness ${PROJECT_NAME}_rviz_test_support ${PROJECT_NAME} ${catkin_LIBRARIES}
                        Qt5::Widgets)
  target_compile_options(test_robustness PRIVATE ${${PROJECT_NAME}_WARNINGS})
  target_compile_definitions(test_robustness PRIVATE
    RVIZ_PROJECTOR_TEST_CONFIGS="${CMAKE_CURRENT_SOURCE_DIR}/test/rviz/configs")
  add_dependencies(tests test_robustness)
  foreach(part path camera config lifecycle)
    add_rostest(test/rviz/robustness_${part}.test DEPENDENCIES test_robustness)
  endforeach()
endif()
