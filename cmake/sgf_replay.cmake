# sgf_replay: replays an SGF game record onto a stone node's board (README.md, "Go points and
# game records"). Included by CMakeLists.txt. The decisions (options, the calls in order) form a
# ROS-free library the tests call directly; the executable adds the ROS service clients.
add_library(virtual_go_replay
  src/replay/replay_options.cpp
  src/replay/replay_runner.cpp)
target_link_libraries(virtual_go_replay PUBLIC virtual_go_core)

add_executable(sgf_replay
  src/apps/sgf_replay_main.cpp
  src/replay/ros_board_services.cpp)
# ROS's headers and the generated virtual_go/PlaceStone.h come from the folder-wide
# include_directories of cmake/node.cmake (as for bag_report).
target_link_libraries(sgf_replay virtual_go_replay ${catkin_LIBRARIES})
add_dependencies(sgf_replay ${${PROJECT_NAME}_EXPORTED_TARGETS} ${catkin_EXPORTED_TARGETS})

install(TARGETS virtual_go_replay sgf_replay
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
