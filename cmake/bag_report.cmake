# bag_report: inspects rosbags of the stone node (README.md, "Recording, replay and bag_report"). Included by CMakeLists.txt.
# The analysis (stamps, segments, prediction, checks, output) and the rosbag reader form a
# library so the tests can call them directly; main() only wires them together.
include_directories(${catkin_INCLUDE_DIRS})

add_library(virtual_go_bag_report
  src/bag/stamp_statistics.cpp
  src/bag/physics_check.cpp
  src/bag/stone_overlap.cpp
  src/bag/stone_island.cpp
  src/bag/thresholds.cpp
  src/bag/options.cpp
  src/bag/report.cpp
  src/bag/bag_structure.cpp
  src/bag/bag_reader.cpp)
# ROS's headers and the generated messages' come from this folder's include_directories
# (above; generate_messages() adds the devel space's include folder): exported PUBLIC they would
# be this machine's absolute paths (catkin_lint: external_interface_path, external_directory).
target_include_directories(virtual_go_bag_report PUBLIC include)
# virtual_go_sim: the event type and its reason names (sim/segment_event.h), shared with the node.
target_link_libraries(virtual_go_bag_report PUBLIC ${catkin_LIBRARIES} virtual_go_sim)
# The reader includes the generated virtual_go/StoneInfo.h and StoneEvent.h.
add_dependencies(virtual_go_bag_report ${${PROJECT_NAME}_EXPORTED_TARGETS}
  ${catkin_EXPORTED_TARGETS})

add_executable(bag_report src/apps/bag_report_main.cpp)
target_link_libraries(bag_report virtual_go_bag_report)
set_target_properties(bag_report PROPERTIES
  RUNTIME_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION})

install(TARGETS virtual_go_bag_report bag_report
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
