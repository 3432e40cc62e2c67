# Tests of the stone node. Included by CMakeLists.txt inside if(CATKIN_ENABLE_TESTING).

# The ROS-free adapter (clock, parameters, requests, outputs, simulation and its controls,
# pacer, mesh file, clock watch): gtest, no master.
catkin_add_gtest(node_adapter_test
  test/sim/test_sim_clock.cpp
  test/sim/test_stone_config.cpp
  test/sim/test_stone_parameters.cpp
  test/sim/test_state_request.cpp
  test/sim/test_state_output.cpp
  test/sim/test_stone_simulation.cpp
  test/sim/test_stone_simulation_board.cpp
  test/sim/test_stone_simulation_controls.cpp
  test/sim/test_stone_simulation_place.cpp
  test/sim/test_click_placement.cpp
  test/sim/test_stone_simulation_names.cpp
  test/sim/test_stone_simulation_pose_room.cpp
  test/sim/test_sim_pacer.cpp
  test/sim/test_stone_states.cpp
  test/sim/test_mesh_file.cpp
  test/sim/test_clock_watch.cpp
  test/sim/test_sim_diagnostics.cpp)
target_link_libraries(node_adapter_test virtual_go_sim GTest::gtest_main)
# Checks README.md's parameter table against the code.
target_compile_definitions(node_adapter_test PRIVATE VG_README="${PROJECT_SOURCE_DIR}/README.md")

# The node with a real master (rostest). One gtest binary holds every suite; each .test file
# starts the node with its config and picks a suite with --gtest_filter.
add_rostest_gtest(stone_node_rostest test/ros/stone_node_tf.test
  test/support/rostest_main.cpp
  test/ros/test_stone_node_tf.cpp
  test/ros/test_stone_node_services.cpp
  test/ros/test_stone_node_sim_time.cpp
  test/ros/test_stone_node_params.cpp
  test/ros/test_stone_node_board.cpp
  test/ros/test_stone_node_controls.cpp
  test/ros/test_stone_node_stones.cpp
  test/ros/test_stone_node_place.cpp
  test/ros/test_stone_node_free_fall.cpp)
target_link_libraries(stone_node_rostest ${catkin_LIBRARIES} GTest::gtest)
target_compile_definitions(stone_node_rostest PRIVATE STONE_NODE_PATH="$<TARGET_FILE:stone_node>")
add_dependencies(stone_node_rostest stone_node ${${PROJECT_NAME}_EXPORTED_TARGETS}
  ${catkin_EXPORTED_TARGETS})
foreach(node_test
    stone_node_tf_constant_omega
    stone_node_services
    stone_node_sim_time
    stone_node_params
    stone_node_hz
    stone_node_board
    stone_node_controls
    stone_node_own_clock
    stone_node_stones
    stone_node_place
    stone_node_free_fall)
  add_rostest(test/ros/${node_test}.test DEPENDENCIES stone_node_rostest stone_node)
endforeach()

# rviz under Xvfb (the test starts Xvfb and rviz itself and reads a screenshot).
add_rostest(test/ros/rviz_smoke.test DEPENDENCIES stone_node)

# README.md, pasted: its commands run as a user types them (test/ros/test_readme_commands.py).
add_rostest(test/ros/readme_commands.test DEPENDENCIES stone_node bag_report sgf_replay)
# rviz's Publish Point (/clicked_point) places stones (test/ros/test_stone_node_click.py).
add_rostest(test/ros/stone_node_click.test DEPENDENCIES stone_node)
# use_sim_time without /clock: the node says it waits (test/ros/test_stone_node_clock_wait.py).
add_rostest(test/ros/stone_node_clock_wait.test DEPENDENCIES stone_node)

# The board's drawing for rviz (ROS-free): gtest, no master.
catkin_add_gtest(board_drawing_test test/sim/test_board_drawing.cpp)
target_link_libraries(board_drawing_test virtual_go_sim GTest::gtest_main)

# Every stone's MarkerArray (ROS message types, no master): gtest.
catkin_add_gtest(stone_markers_test test/ros/test_stone_markers.cpp src/ros/stone_markers.cpp)
target_include_directories(stone_markers_test PRIVATE include)
target_link_libraries(stone_markers_test ${catkin_LIBRARIES} GTest::gtest_main)
add_dependencies(stone_markers_test ${catkin_EXPORTED_TARGETS})
