// What an integrator carries from one step of one body to the next. The body's owner keeps one
// cache per body, hands it to every Integrator::advance() of that body, and calls invalidate()
// whenever it replaced the body's state from outside (a reset, a teleport, later an impact):
// the integrator never guesses that from the state itself, and keeps nothing per body.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>

#include "virtual_go/flight/exact_motion.h"

namespace virtual_go {

class Integrator;

// ExactIntegrator's part: the closed form anchored at a state, and the two fixed rotations of
// one step of dt_s.
struct ExactStepCache {
  const Integrator* integrator = nullptr;  // the integrator that anchored; nullptr: none
  double dt_s = 0.0;
  std::optional<ExactMotion> anchor;
  std::int64_t steps_since_anchor = 0;
  bool rotating = false;
  Eigen::Quaterniond left_step = Eigen::Quaterniond::Identity();
  Eigen::Quaterniond right_step = Eigen::Quaterniond::Identity();
};

class FlightCache {
 public:
  // The body's state was replaced: the next step starts afresh from the state it is given.
  void invalidate() { exact_.integrator = nullptr; }
  // True while an integrator continues from what it kept (the state was not replaced since).
  bool holds_anchor() const { return exact_.integrator != nullptr; }

  ExactStepCache& exact() { return exact_; }

 private:
  ExactStepCache exact_;
};

}  // namespace virtual_go
