# Stability stress suite: 10^7 exact steps, a 10^6-step splitting run, extreme inputs
# and a fixed-seed fuzz of the core's public entry points. About a minute at most in all.
catkin_add_gtest(test_stress
  test/stress/test_stress_long.cpp
  test/stress/test_stress_extremes.cpp
  test/stress/test_stress_fuzz.cpp)
target_link_libraries(test_stress virtual_go_core GTest::gtest_main)
# Optimised even in a Debug build of the package: the long runs are mostly loop overhead here.
target_compile_options(test_stress PRIVATE -O2)

# Seeded fuzz of the contact core (issue 19): 10^3 random states (VG_FUZZ_STATES sets another
# count; 10^4 finds one state above the work bound, an open finding)
# in every regime and material, each 2 s with a work budget.
catkin_add_gtest(test_contact_fuzz test/stress/test_contact_fuzz.cpp)
target_link_libraries(test_contact_fuzz virtual_go_core GTest::gtest_main)
target_compile_options(test_contact_fuzz PRIVATE -O2)
