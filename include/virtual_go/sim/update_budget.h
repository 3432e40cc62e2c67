// How much physics one update of the simulation may do before it returns, so that the node's
// single thread gets back to its services and timers. Asked between physics steps (at least
// one step is always taken, so the simulation never stops); ROS-free: the node gives a
// steady-clock deadline, tests count the questions.
#pragma once

#include <chrono>
#include <cstdint>

namespace virtual_go {

class UpdateBudget {
 public:
  virtual ~UpdateBudget() = default;
  // Asked before each physics step after the first of an update: true stops the update there;
  // the steps not taken come at the next update (the simulation falls behind ROS time).
  virtual bool spent() = 0;
};

// Never spent: every step due is taken (tests, tools that do not serve anyone meanwhile).
class UnlimitedBudget : public UpdateBudget {
 public:
  bool spent() override { return false; }
};

// Spent once the steady clock passes start + allowance.
class DeadlineBudget : public UpdateBudget {
 public:
  explicit DeadlineBudget(std::chrono::nanoseconds allowance)
      : deadline_(std::chrono::steady_clock::now() + allowance) {}
  bool spent() override { return std::chrono::steady_clock::now() >= deadline_; }

 private:
  std::chrono::steady_clock::time_point deadline_;
};

// Wall time the node lets one update work: half a tick period, at most 0.1 s. The other half
// is left for services, publishing and the other timers.
std::chrono::nanoseconds update_allowance(double rate_hz);

}  // namespace virtual_go
