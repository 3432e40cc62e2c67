// Start-up parameters: each invalid one makes stone_node exit non-zero with a FATAL message
// naming it; --help needs no master. Runs the real binary (path from CMake).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

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
      {"type", "_dt:=fast", "~dt: must be a number"},
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

TEST(StoneNodeParams, HelpNeedsNoMaster) {
  for (const char* flag : {"--help", "-h"}) {
    // A master URI where nothing listens: --help must not try to connect.
    const Outcome out = run(flag, "ROS_MASTER_URI=http://127.0.0.1:9");
    EXPECT_EQ(out.exit_code, 0) << out.output;
    EXPECT_NE(out.output.find("usage: rosrun virtual_go stone_node"), std::string::npos);
    EXPECT_NE(out.output.find("~set_angular_velocity"), std::string::npos);
  }
}
