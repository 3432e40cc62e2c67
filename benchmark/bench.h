// Shared types of the work-precision benchmark: a scenario, one method under test, a sample.
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/flight/integrator_registry.h"

namespace vg_bench {

struct Scenario {
  std::string name;
  std::string description;
  virtual_go::MotionSetup setup;        // our model and gravity
  virtual_go::RigidBodyState initial;   // angular momentum set from initial_omega_world
  Eigen::Vector3d initial_omega_world;  // rad/s, what the peers are given
  double mass;                          // kg
  Eigen::Vector3d peer_inertia_body;    // principal moments the peers simulate, kg m^2
  double duration;                      // s
};

// What every method reports after a step, in our conventions (q body->world, world frame).
struct Sample {
  Eigen::Vector3d position_world;
  Eigen::Quaterniond orientation;
  Eigen::Vector3d velocity_world;
  Eigen::Vector3d omega_world;
};

// A method refuses a configuration it cannot run (reason goes into the table).
class NotRun : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Method {
 public:
  virtual ~Method() = default;
  virtual std::string name() const = 0;
  virtual bool is_peer() const { return true; }
  // Puts the body in the scenario's initial state for steps of dt (not timed).
  virtual void reset(const Scenario& scenario, double dt) = 0;
  virtual void step() = 0;  // one step of dt (timed)
  virtual Sample sample() const = 0;
  // Non-empty when the engine flagged the run as failed although the state looks finite.
  virtual std::string failure() const { return ""; }
};

// Peer engines (peers.cpp). Each prints its relevant defaults once to `notes`.
std::unique_ptr<Method> make_bullet(double mass_scale, std::vector<std::string>& notes);
std::unique_ptr<Method> make_ode(bool finite_rotation, std::vector<std::string>& notes);
std::unique_ptr<Method> make_mujoco(bool rk4, std::vector<std::string>& notes);
void init_peers();
void shutdown_peers();

}  // namespace vg_bench
