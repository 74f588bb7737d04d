# projector_host: the projector output of a .rviz config without rviz's GUI (issue 13).
# Included from CMakeLists.txt after the plugin library target.
# diagnostic_updater and std_srvs come with the package's catkin components, X11 (the display check
# before Qt starts) from CMakeLists.txt.

add_executable(projector_host
  src/host/host_config.cpp
  src/host/host_curtain.cpp
  src/host/host_diagnostics.cpp
  src/host/host_display_status.cpp
  src/host/host_file_watcher.cpp
  src/host/host_options.cpp
  src/host/host_projector_status.cpp
  src/host/host_reload_service.cpp
  src/host/host_session.cpp
  src/host/projector_host_main.cpp
  src/host/x_display_check.cpp
)
target_include_directories(projector_host SYSTEM PRIVATE ${X11_INCLUDE_DIR})
target_link_libraries(projector_host ${PROJECT_NAME} ${catkin_LIBRARIES} ${X11_LIBRARIES} Qt5::Widgets)
target_compile_options(projector_host PRIVATE ${${PROJECT_NAME}_WARNINGS})
add_dependencies(projector_host ${catkin_EXPORTED_TARGETS})
install(TARGETS projector_host
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION}
)
