# gtest suite of virtual_go_core: one binary per concept, no ROS master needed.
# Included by CMakeLists.txt inside if(CATKIN_ENABLE_TESTING).
foreach(core_test
    test_mass_properties
    test_stone
    test_tessellation
    test_rotation
    test_rigid_body
    test_free_fall
    test_torque_free_motion
    test_conservation
    test_convergence
    test_constant_omega
    test_bad_input)
  catkin_add_gtest(${core_test} test/${core_test}.cpp)
  target_link_libraries(${core_test} virtual_go_core GTest::gtest_main)
endforeach()
