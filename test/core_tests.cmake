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

# Contact work (issue 10): one binary per concept, in folders mirroring src/.
foreach(area_test geometry/test_lens_geometry go/test_board contact/test_material
    contact/test_plane_region contact/test_lens_on_plane contact/test_plane_contact_dynamics
    contact/test_plane_contact)
  get_filename_component(test_name ${area_test} NAME)
  catkin_add_gtest(${test_name} test/${area_test}.cpp)
  target_link_libraries(${test_name} virtual_go_core GTest::gtest_main)
endforeach()
