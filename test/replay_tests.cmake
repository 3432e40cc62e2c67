# Tests of sgf_replay. Included by CMakeLists.txt inside if(CATKIN_ENABLE_TESTING), after
# test/go_tests.cmake (which finds GNU Go and names the game records).

# The ROS-free part: options, and the calls in order against a recording fake. gtest, no master.
catkin_add_gtest(test_replay test/replay/test_replay_options.cpp test/replay/test_replay_runner.cpp)
target_link_libraries(test_replay virtual_go_replay GTest::gtest_main)
# Checks README.md's option and exit code tables against the code.
target_compile_definitions(test_replay PRIVATE VG_README="${PROJECT_SOURCE_DIR}/README.md")

# The executable against a stand-in for the node (the node's ~place and ~remove come later):
# a Python node serving ~clear/~place/~remove that records the calls; the board they leave must
# be GNU Go's for the same record.
# Paths reach the test through a file in the devel space (found with catkin's
# find_in_workspaces), never as rostest arguments: catkin names a rostest's targets after its
# arguments, so a path there would grow the names with the checkout path (issue 18).
string(REPLACE ";" " " self_play_games "${gnugo_games}")
file(WRITE ${CATKIN_DEVEL_PREFIX}/share/${PROJECT_NAME}/test_data_paths.txt
  "game ${VG_KIGO_GAMES}/Honinbo-51-5.sgf\ngnugo ${VG_GNUGO}\nselfplay ${self_play_games}\n")
add_rostest(test/replay/sgf_replay.test DEPENDENCIES sgf_replay)
# Also GNU Go's self-play games (test/go_tests.cmake makes them).
add_rostest(test/replay/sgf_replay_node.test DEPENDENCIES sgf_replay stone_node
  gnugo_selfplay_games)
