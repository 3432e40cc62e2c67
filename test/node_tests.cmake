# Tests of the stone node. Included by CMakeLists.txt inside if(CATKIN_ENABLE_TESTING).

# The ROS-free adapter (clock, parameters, requests, simulation): gtest, no master.
catkin_add_gtest(node_adapter_test
  test/sim_clock_test.cpp
  test/stone_config_test.cpp
  test/state_request_test.cpp
  test/stone_simulation_test.cpp)
target_link_libraries(node_adapter_test virtual_go_sim GTest::gtest_main)
