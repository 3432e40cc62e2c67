// Writes bags of a stone on the board for the bag_report contact tests, with the rosbag C++ API:
// the core's World advanced on a fixed grid, written as the node writes them (/tf, ~odom, ~info,
// ~events with the event's instant as a whole-ns stamp plus the sub-ns offset), no node and no
// master. Corruptions of single samples check that bag_report names the check that catches them.
#pragma once

#include <cstdint>
#include <string>

#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/contact/material.h"

namespace virtual_go_test {

// One sample altered after the World produced it (none by default).
enum class Corruption {
  none,
  energy_bump,        // a sample inside a contact segment: linear speed x (1 + 1e-6)
  pushed_into_board,  // a sample inside a contact segment: 1e-6 m lower than the World had it
  rest_ulp,           // a sample inside a rest segment: x moved by one ulp
  flight_rotation,    // a sample inside a flight segment (not the first): rotated 1e-6 rad about z
};

struct WorldRunSpec {
  virtual_go::RigidBodyState initial;  // world frame, at t = 0
  double duration_s = 1.0;
  std::int64_t dt_ns = 2'000'000;  // the grid (and ~info's dt and rate)
  std::int64_t start_ns = 100'000'000'000;
  virtual_go::ContactMaterial material;  // board and table alike
  Corruption corruption = Corruption::none;
};

struct WorldRunSummary {
  std::size_t odom = 0;    // samples written
  std::size_t events = 0;  // ~events written (the start and the World's)
  std::size_t impacts = 0;
  std::size_t contacts = 0;  // slide, roll, rim events
  std::size_t rests = 0;
  bool corrupted = false;     // the corruption found a sample to alter
  double rest_time_s = -1.0;  // the last rest event's time, s since the start; -1: none
};

// The default Go stone (size 33 slate) on the default board; overwrites path.
WorldRunSummary write_world_bag(const std::string& path, const WorldRunSpec& spec);

}  // namespace virtual_go_test
