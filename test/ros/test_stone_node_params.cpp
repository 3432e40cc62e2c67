// Start-up parameters: each invalid one makes stone_node exit non-zero with a FATAL message
// naming it; --help needs no master. Runs the real binary (path from CMake).
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#ifndef STONE_NODE_PATH
#error "STONE_NODE_PATH must name the stone_node binary"
#endif

namespace {

struct Outcome {
  int exit_code;
  std::string output;
};

Outcome run(const std::string& arguments, const std::string& environment = "") {
  const std::string command =
      environment + " timeout 30 " STONE_NODE_PATH " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return {-1, "popen failed"};
  std::string output;
  std::array<char, 512> buffer;
  while (fgets(buffer.data(), buffer.size(), pipe) != nullptr) output += buffer.data();
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

}  // namespace

TEST(StoneNodeParams, InvalidParametersAreFatalAndNamed) {
  struct Case {
    const char* name;
    const char* arguments;
    const char* expected;
  };
  const Case cases[] = {
      {"dt_fraction", "_dt:=0.0009765625", "~dt: must be a whole number of nanoseconds"},
      {"rate", "_rate:=-5.0", "~rate:"},
      // Used to abort in ros::Duration (period too long) or busy-loop (period 0 ns).
      {"rate_tiny", "_rate:=1.0e-12", "~rate: must be between"},
      {"rate_huge", "_rate:=1.0e12", "~rate: must be between"},
      {"model", "_model:=newtonian", "~model:"},
      {"integrator", "_integrator:=verlet", "~integrator:"},
      {"gravity", "_gravity:=[0.0,0.0]", "~gravity: must be a list of 3 numbers"},
      {"color", "_stone/color:=green", "~stone/color:"},
      {"size", "_stone/size:=29", "~stone/size:"},
      {"auto_reset", "_auto_reset_period:=0.0005", "~auto_reset_period: must be 0 (never) or"},
      {"orientation", "_initial/orientation:=[0.0,0.0,0.0,0.0]", "~initial/orientation"},
      {"omega", "_initial/angular_velocity:=[0.0,0.0,1.0e6]", "~initial/angular_velocity"},
      {"type", "_dt:=fast", "~dt: must be a number, got 'fast'"},
      // issue 8: blamed on ~stone/size.
      {"width_small", "_stone/width:=0.005",
       "~stone/width: stone width 0.005 m must be more than the height 0.0092 m"},
      // issue 8: accepted, with subnormal moments (omega_z 29.875 published for 30).
      {"mass_subnormal", "_stone/mass:=1.0e-303",
       "~stone/mass: the mass must be between ~min_mass 1e-06 and ~max_mass 1000 kg"},
      {"bound_beyond_cap", "_max_speed:=1.0e+9", "~max_speed: must be positive and at most"},
      // A typo is warned about (before the FATAL that ends this run).
      {"unknown", "_rat:=5.0 _rate:=-5.0", "ignoring unknown parameter ~rat (see"},
  };
  for (const Case& c : cases) {
    const Outcome out = run(std::string("__name:=bad_") + c.name + " " + c.arguments);
    EXPECT_NE(out.exit_code, 0) << c.name << ":\n" << out.output;
    EXPECT_NE(out.output.find("FATAL"), std::string::npos) << c.name << ":\n" << out.output;
    EXPECT_NE(out.output.find(c.expected), std::string::npos)
        << c.name << ": expected '" << c.expected << "' in:\n"
        << out.output;
  }
}

// issue 8: ~initial/velocity [1.7564270946e+308, 0, 0] and ~gravity [0, 0, -8.574e307] were
// accepted, and 1.024 s later the node exited with a FATAL that named no parameter ("time
// 1.024 s is too large: the state overflows"). They are refused at start-up, naming the
// parameter, the value and the limit. (Lists cannot be given as _param:= arguments, which
// roscpp reads as strings: they are set on the master, under the node's name.)
TEST(StoneNodeParams, AbsurdVectorsAreFatalWithTheirLimit) {
  struct Case {
    const char* node;
    const char* parameter;
    std::vector<double> value;
    const char* expected;
  };
  const Case cases[] = {
      {"bad_velocity_absurd",
       "initial/velocity",
       {1.7564270946e+308, 0.0, 0.0},
       "~initial/velocity: |v| = 1.7564270946e+308 m/s exceeds ~max_speed 1000 m/s"},
      {"bad_gravity_absurd",
       "gravity",
       {0.0, 0.0, -8.574e307},
       "~gravity: |g| = 8.574e+307 m/s^2 exceeds ~max_gravity 1000 m/s^2"},
      {"bad_position_absurd",
       "initial/position",
       {0.0, 1e300, 0.0},
       "~initial/position: distance from the world origin = 1e+300 m exceeds ~max_distance"},
  };
  for (const Case& c : cases) {
    const std::string name = std::string("/") + c.node + "/" + c.parameter;
    ros::param::set(name, c.value);
    const Outcome out = run(std::string("__name:=") + c.node);
    ros::param::del(name);
    EXPECT_NE(out.exit_code, 0) << c.node << ":\n" << out.output;
    EXPECT_NE(out.output.find("FATAL"), std::string::npos) << c.node << ":\n" << out.output;
    EXPECT_NE(out.output.find(c.expected), std::string::npos)
        << c.node << ": expected '" << c.expected << "' in:\n"
        << out.output;
  }
}

// issue 19: the string "true" was printed unquoted, reading as the boolean it was refused for.
// Strings are quoted, also inside a list. (Set on the master: a _param:= argument cannot give
// the string "true".)
TEST(StoneNodeParams, TypeErrorsQuoteStrings) {
  ros::param::set("/bad_type_string_bool/board/enabled", std::string("true"));
  Outcome out = run("__name:=bad_type_string_bool");
  ros::param::del("/bad_type_string_bool/board/enabled");
  EXPECT_NE(out.exit_code, 0) << out.output;
  EXPECT_NE(out.output.find("~board/enabled: must be true or false, got 'true'"), std::string::npos)
      << out.output;
  XmlRpc::XmlRpcValue list;
  list[0] = 0.5;
  list[1] = std::string("a");
  list[2] = 1;
  ros::param::set("/bad_type_list/initial/position", list);
  out = run("__name:=bad_type_list");
  ros::param::del("/bad_type_list/initial/position");
  EXPECT_NE(out.exit_code, 0) << out.output;
  EXPECT_NE(out.output.find("~initial/position: must be a list of 3 numbers, got [0.5, 'a', 1]"),
            std::string::npos)
      << out.output;
}

TEST(StoneNodeParams, HelpNeedsNoMaster) {
  for (const char* flag : {"--help", "-h"}) {
    // A master URI where nothing listens: --help must not try to connect.
    const Outcome out = run(flag, "ROS_MASTER_URI=http://127.0.0.1:9");
    EXPECT_EQ(out.exit_code, 0) << out.output;
    EXPECT_NE(out.output.find("usage: rosrun virtual_go stone_node"), std::string::npos);
    EXPECT_NE(out.output.find("~set_angular_velocity"), std::string::npos);
  }
}

// issue 19: the long ~contact/* names pushed the unit column out of line. Every parameter line
// has its unit (or, without one, its help) at the same column as every other.
TEST(StoneNodeParams, HelpColumnsLineUp) {
  const Outcome out = run("--help", "ROS_MASTER_URI=http://127.0.0.1:9");
  ASSERT_EQ(out.exit_code, 0) << out.output;
  const std::size_t section = out.output.find("Parameters (name, unit, meaning; default):\n");
  ASSERT_NE(section, std::string::npos) << out.output;
  std::istringstream lines(out.output.substr(section));
  std::set<std::size_t> unit_columns, help_columns;
  std::size_t longest = 0, parameters = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("  ~", 0) != 0) continue;
    ++parameters;
    const std::size_t name_end = line.find(' ', 2);
    longest = std::max(longest, name_end);
    const std::size_t next = line.find_first_not_of(' ', name_end);
    // The unit is one word of at most 7 characters; anything else is the help.
    const std::size_t next_end = line.find(' ', next);
    const bool is_unit = next_end != std::string::npos && next_end - next <= 7 &&
                         line.find_first_not_of(' ', next_end) - next == 8;
    (is_unit ? unit_columns : help_columns).insert(next);
  }
  EXPECT_GT(parameters, 30u);
  ASSERT_EQ(unit_columns.size(), 1u) << out.output;
  EXPECT_GT(*unit_columns.begin(), longest) << "a name runs into the unit column";
  for (std::size_t c : help_columns) EXPECT_EQ(c, *unit_columns.begin() + 8) << out.output;
}
