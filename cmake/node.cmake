# The stone node: a ROS-free adapter library (clock, config, requests, simulation; gtested
# without a master) and the thin ROS layer on top of it.
include_directories(${catkin_INCLUDE_DIRS})

add_library(virtual_go_sim
  src/sim/sim_clock.cpp
  src/sim/stone_config.cpp
  src/sim/stone_parameters.cpp
  src/sim/state_request.cpp
  src/sim/segment_event.cpp
  src/sim/stone_states.cpp
  src/sim/state_output.cpp
  src/sim/stone_simulation.cpp
  src/sim/stone_simulation_requests.cpp
  src/sim/stone_simulation_planning.cpp
  src/sim/stone_simulation_timeline.cpp
  src/sim/stone_simulation_step.cpp
  src/sim/stone_simulation_world.cpp
  src/sim/stone_simulation_events.cpp
  src/sim/mesh_file.cpp
  src/sim/clock_watch.cpp
  src/sim/update_budget.cpp
  src/sim/board_drawing.cpp
  src/sim/sim_diagnostics.cpp
  src/sim/sim_pacer.cpp
  src/sim/click_placement.cpp)
target_link_libraries(virtual_go_sim PUBLIC virtual_go_core)

add_executable(stone_node
  src/apps/stone_node_main.cpp
  src/ros/stone_node.cpp
  src/ros/stone_node_help.cpp
  src/ros/param_reader.cpp
  src/ros/stone_messages.cpp
  src/ros/board_markers.cpp
  src/ros/stone_markers.cpp)
target_link_libraries(stone_node virtual_go_sim ${catkin_LIBRARIES})
add_dependencies(stone_node ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS})

install(TARGETS stone_node virtual_go_sim
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
