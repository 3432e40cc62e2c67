# gtest suite of virtual_go_core: one binary per test file, named after it, no ROS master.
# Included by CMakeLists.txt inside if(CATKIN_ENABLE_TESTING).
foreach(core_test
    common/test_bad_input
    common/test_formatting
    common/test_name_table
    common/test_sim_time
    geometry/test_rotation
    geometry/test_tessellation
    body/test_mass_properties
    body/test_rigid_body_state
    body/test_rigid_body
    go/test_stone
    go/test_stone_set
    flight/test_integrator_registry
    flight/test_flight_cache
    flight/test_free_fall
    flight/test_torque_free_motion
    flight/test_conservation
    flight/test_convergence
    flight/test_constant_omega
    geometry/test_lens_geometry
    geometry/test_lens_distance
    geometry/test_lens_pair_distance
    go/test_board
    go/test_board_distance
    go/test_go_point
    go/test_sgf
    go/test_go_position
    go/test_game_replay
    contact/test_material
    contact/test_bracketed_root
    contact/test_flight_gap_bound
    contact/test_pair_gap_bound
    contact/test_time_of_impact
    contact/test_pair_time_of_impact
    contact/test_impact
    contact/test_pair_impact
    contact/test_coulomb_plastic_impulse
    contact/test_simultaneous_impacts
    contact/test_plane_region
    contact/test_lens_on_plane
    contact/test_dop853
    contact/test_plane_contact_dynamics
    contact/test_plane_contact
    world/test_world_event
    world/test_world_body
    world/test_support_plane
    world/test_flight_track
    world/test_nonsmooth_contact
    world/test_island_contact
    world/test_island_convergence
    world/test_island_impulses
    world/test_nonsmooth_island_joint
    world/test_broad_phase
    world/test_world
    world/test_world_edges
    world/test_world_robustness
    world/test_world_stones
    world/test_world_contacts
    world/test_world_pair_impacts
    world/test_world_cradle
    world/test_world_crowd
    world/test_static_balance
    world/test_stone_placement
    world/test_world_resting_cost
    world/test_world_reach_bound
    world/test_world_full_board_throw)
  get_filename_component(target ${core_test} NAME)
  catkin_add_gtest(${target} test/${core_test}.cpp)
  target_link_libraries(${target} virtual_go_core GTest::gtest_main)
  # Tests that hold README.md's tables to the code read it from the source tree.
  target_compile_definitions(${target} PRIVATE VG_README="${PROJECT_SOURCE_DIR}/README.md")
endforeach()

