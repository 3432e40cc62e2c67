# The sources of virtual_go_core (Eigen only, no ROS), by area, relative to the package root.
# The one list of what the core is: CMakeLists.txt builds the library from it and
# benchmark/CMakeLists.txt compiles the same files with its own flags.
set(VG_CORE_SOURCES
  src/common/formatting.cpp
  src/common/validation.cpp
  src/geometry/rotation.cpp
  src/geometry/lens_shape.cpp
  src/geometry/tessellation.cpp
  src/geometry/lens_geometry.cpp
  src/geometry/lens_distance.cpp
  src/body/mass_properties.cpp
  src/body/rigid_body_state.cpp
  src/body/motion_model.cpp
  src/body/rigid_body.cpp
  src/flight/integrator.cpp
  src/flight/integrator_registry.cpp
  src/flight/euler_integrator.cpp
  src/flight/rk4_integrator.cpp
  src/flight/splitting_integrator.cpp
  src/flight/exact_integrator.cpp
  src/flight/exact_motion.cpp
  src/go/stone_sizes.cpp
  src/go/stone_materials.cpp
  src/go/stone.cpp
  src/go/board.cpp
  src/go/board_distance.cpp
  src/contact/material.cpp
  src/contact/flight_gap_bound.cpp
  src/contact/time_of_impact.cpp
  src/contact/impact.cpp
  src/contact/plane_region.cpp
  src/contact/lens_on_plane.cpp
  src/contact/plane_contact_dynamics.cpp
  src/contact/plane_contact.cpp)
