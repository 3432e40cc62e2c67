// stone_node: the Go stone simulator as a ROS node (see stone_node --help).
#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <thread>

#include "virtual_go/ros/stone_node.h"
#include "virtual_go/ros/stone_node_help.h"

namespace {

std::atomic<bool> g_sigint{false};
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");

void on_sigint(int) { g_sigint = true; }

// SIGINT (and rosnode kill) must stop the node within a second even if a callback does not
// return (a physics step that runs away: issue 19). The stop is asked of roscpp as usual; if
// the spin has not ended kGracePeriod later, the process ends here, saying why.
constexpr std::chrono::milliseconds kGracePeriod{800};

void stop_watch(const std::atomic<bool>& spin_ended) {
  while (!spin_ended) {
    if (g_sigint || !ros::ok()) {
      ros::requestShutdown();
      const auto deadline = std::chrono::steady_clock::now() + kGracePeriod;
      while (!spin_ended && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
      if (spin_ended) return;
      std::fprintf(stderr,
                   "stone_node: a callback was still running %lld ms after the shutdown "
                   "request (a physics step that does not finish); exiting without it\n",
                   static_cast<long long>(kGracePeriod.count()));
      std::fflush(stderr);
      std::_Exit(1);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "-h") == 0 || std::strcmp(argv[i], "--help") == 0) {
      std::fputs(virtual_go::stone_node_help().c_str(), stdout);
      return 0;
    }
  }
  ros::init(argc, argv, "stone", ros::init_options::NoSigintHandler);
  std::signal(SIGINT, on_sigint);
  // Outlives the node: when the last NodeHandle goes, roscpp shuts down and drops log output,
  // which would swallow the FATAL below.
  ros::NodeHandle nh, private_nh("~");
  std::atomic<bool> spin_ended{false};
  std::thread watch(stop_watch, std::cref(spin_ended));
  int code = 0;
  try {
    virtual_go::StoneNode node(nh, private_nh);
    // ros::spin() with the stop flag checked between callbacks (roscpp's own SIGINT handler
    // is replaced by on_sigint).
    while (ros::ok() && !g_sigint)
      ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.05));
  } catch (const virtual_go::ConfigError& e) {
    ROS_FATAL("stone_node: invalid parameter %s", e.what());
    code = 1;
  } catch (const std::exception& e) {
    // Anything else (roscpp, tf2, the core) must still end with a message and a failure code,
    // not std::terminate.
    ROS_FATAL("stone_node: %s", e.what());
    code = 1;
  }
  spin_ended = true;
  watch.join();
  return code;
}
