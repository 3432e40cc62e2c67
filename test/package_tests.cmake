# Tests of the package's build itself: a configure from a deep checkout path, catkin_lint.
# Included by CMakeLists.txt inside if(CATKIN_ENABLE_TESTING).

# Offline Python unittests (no master, so not rostest): catkin's run_tests wrapper runs each,
# rosunit writes its JUnit file where the wrapper (and scripts/count_test_results.py) look; a
# test that writes none counts as failed (the wrapper's MISSING-*.xml). The wrapper runs the
# command through a shell, as one string.
function(vg_add_python_test name)
  set(result "${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME}/python-${name}.xml")
  catkin_run_tests_target(python ${name} python-${name}.xml
    COMMAND "\"${PYTHON_EXECUTABLE}\" \"${PROJECT_SOURCE_DIR}/test/package/test_${name}.py\" \"--gtest_output=xml:${result}\"")
endfunction()

# A copy of the sources configured from a 200-character checkout path (about 10 s).
vg_add_python_test(configure_long_path)
# catkin_lint -W2 --strict on the package (about 2 s).
vg_add_python_test(catkin_lint)
