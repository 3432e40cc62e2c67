# The Go rules held to GNU Go (Debian's gnugo), a program nobody here wrote. Included by
# CMakeLists.txt inside if(CATKIN_ENABLE_TESTING). The game records come from two places:
# Debian's kigo package (scripts/setup.sh fetches them into the build folder, as GPL game
# records they are not in this repository) and GNU Go self-play, generated below once per seed
# (a minute or two each; regenerated only when the generator changes).
find_program(VG_GNUGO gnugo PATHS /usr/games NO_DEFAULT_PATH)
find_program(VG_GNUGO gnugo)
if(NOT VG_GNUGO)
  message(FATAL_ERROR "GNU Go not found: install gnugo (scripts/setup.sh does)")
endif()
set(VG_KIGO_GAMES ${CMAKE_BINARY_DIR}/test_data/kigo/usr/share/kigo/games)
set(VG_GNUGO_GAMES ${CMAKE_BINARY_DIR}/test_data/gnugo)

# The self-play generator talks GTP itself and links nothing of the package, so a change in the
# core does not make the games again.
# A tool of the tests' set-up, never installed ("test" in its name tells catkin_lint so).
add_executable(gnugo_selfplay_testdata EXCLUDE_FROM_ALL
  test/support/gnugo_selfplay_main.cpp test/support/gtp_engine.cpp)
set(gnugo_games)
foreach(seed 1 2)
  set(game ${VG_GNUGO_GAMES}/selfplay_seed${seed}.sgf)
  add_custom_command(OUTPUT ${game}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${VG_GNUGO_GAMES}
    COMMAND gnugo_selfplay_testdata ${VG_GNUGO} ${seed} ${game}
    DEPENDS gnugo_selfplay_testdata
    COMMENT "GNU Go self-play game, seed ${seed} (a minute or two)")
  list(APPEND gnugo_games ${game})
endforeach()
add_custom_target(gnugo_selfplay_games DEPENDS ${gnugo_games})


catkin_add_gtest(test_gnugo_replay test/go/test_gnugo_replay.cpp test/support/gtp_engine.cpp)
target_link_libraries(test_gnugo_replay virtual_go_core GTest::gtest_main)
target_compile_definitions(test_gnugo_replay PRIVATE VG_GNUGO="${VG_GNUGO}"
  VG_KIGO_GAMES="${VG_KIGO_GAMES}" VG_GNUGO_GAMES="${VG_GNUGO_GAMES}")
add_dependencies(test_gnugo_replay gnugo_selfplay_games)
