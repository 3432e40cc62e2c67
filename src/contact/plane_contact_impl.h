// PlaneContact's state (plane_contact.h): the mode, the integrator at the time reached, the kept
// trajectory and the pending event. Built and driven in plane_contact.cpp (set-up and checks,
// advance(), events); stepped and sampled in plane_contact_stepping.cpp.
#pragma once

#include <limits>
#include <optional>
#include <vector>

#include "plane_contact_laws.h"

namespace virtual_go {

class PlaneContact::Impl {
 public:
  Impl(const PlaneContactSetup& setup, const PlaneRegion& region, const RigidBodyState& state,
       double t0, const PlaneContactOptions& options);

  PlaneContactOutcome advance(double t_end, long max_steps);
  RigidBodyState state_at(double t) const {
    require_sample_time(t);
    return to_rigid_body_state(sample(t));
  }
  PlaneContactForces forces_at(double t) const;

  double time_reached() const { return reached_; }
  bool finished() const { return finished_.has_value(); }
  const PlaneContactMode& mode() const { return mode_; }
  const PlaneContactSetup& setup() const { return laws_.setup(); }
  const PlaneContactCounters& counters() const { return laws_.counters(); }

 private:
  using State = plane_contact_detail::State;
  using Trigger = plane_contact_detail::Trigger;
  using ModeChoice = plane_contact_detail::ModeChoice;

  struct Sample {
    PlaneContactKinematics kinematics;
    PlaneContactMode mode;
  };
  // A piece of the trajectory for state_at: one integrator step (or its part before an event),
  // or the single state right after an event.
  struct Segment {
    double t_begin = 0.0, t_end = 0.0;  // valid range, s
    double energy_begin = 0.0;  // guarded energy at the step's start, J: the cap of its samples
    PlaneContactMode mode;
    bool point = true;  // the state right after an event: y0 holds it
    double h = 0.0;     // the whole step, s (t_end may be cut short by an event)
    State y0, y1;
    dop853::Stages<plane_contact_detail::kStateSize> k;
    std::array<State, 4> dense;  // the dense output's coefficients, once computed
    bool dense_ready = false;
    // A closed-form piece instead of an integrator step: y(t) = y0 + tau rate + tau^2/2 accel,
    // tau = t - t_begin in [0, h] (plane_contact_stepping.cpp, flat_closed_form).
    bool closed_form = false;
    State rate, accel;
  };
  // The kept segments, oldest first, in storage that grows to at most kMaxStoredSegments and is
  // then reused: no heap work per step once it has grown.
  class SegmentRing {
   public:
    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    Segment& operator[](std::size_t i) { return slots_[(head_ + i) % slots_.size()]; }
    const Segment& operator[](std::size_t i) const { return slots_[(head_ + i) % slots_.size()]; }
    Segment& front() { return (*this)[0]; }
    Segment& back() { return (*this)[size_ - 1]; }
    void pop_front() {
      head_ = (head_ + 1) % slots_.size();
      --size_;
    }
    void pop_back() { --size_; }
    // A slot after the last (its old contents are to be overwritten), the oldest dropped when
    // the ring is at its limit.
    Segment& push_back(std::size_t limit);

   private:
    std::vector<Segment> slots_;
    std::size_t head_ = 0, size_ = 0;
  };
  struct PendingEvent {
    double time = 0.0;
    Trigger trigger = Trigger::lift_off;
  };
  struct Finished {
    PlaneContactEvent event;
    double time;
    Sample sample;
  };

  // --- Stepping and sampling (plane_contact_stepping.cpp)
  void refresh_references();
  void take_step();
  // The flat stone on its cap (axis vertical, rolling stuck) sliding and/or spinning down: one
  // closed-form piece up to its first event instead of integrator steps. False when the mode or
  // the state is not that one (nothing changed then).
  bool flat_closed_form();
  void step_in(Segment& segment);
  // Looks for events a span needs (s): one per event resolution or part of one, at least one.
  int looks_within(double span_s) const;
  State state_in(const Segment& segment, double t) const;
  Sample sample(double t) const;
  void start_mode(const ModeChoice& choice, double t, double energy_cap);
  void push_point(double t);
  // A lower bound of the clearance at pose k from the last value found, by its contract
  // (PlaneContactOptions::clearance_m): the value less the farthest a point of the lens can have
  // moved, |x_G - x_anchor| + rho |b - b_anchor| with rho bounding |P - G| over the lens.
  double clearance_floor(const PlaneContactKinematics& k) const;
  void anchor_clearance(const PlaneContactKinematics& k,
                        const plane_contact_detail::EventValues& g);

  // --- Events and outcomes (plane_contact.cpp)
  std::optional<PlaneContactOutcome> process(const PendingEvent& event);
  RigidBodyState to_rigid_body_state(const Sample& s) const;
  PlaneContactOutcome outcome(double t, PlaneContactEvent event, const Sample& s) const;
  void require_sample_time(double t) const;

  plane_contact_detail::PlaneContactLaws laws_;

  PlaneContactMode mode_;
  State y_;      // integrated state at t_ (the end of the last step)
  State rates_;  // dy/dt at t_, when rates_ready_
  bool rates_ready_ = false;
  double t_ = 0.0;                             // integrator time, s
  double h_ = 0.0;                             // next trial step, s
  double energy_cap_ = 0.0;                    // guarded energy at t_, J
  plane_contact_detail::EventValues g_start_;  // event values at t_
  // The clearance where it was last evaluated (pose and value), and whether g_start_ holds only
  // a positive lower bound of it (clearance_floor).
  struct ClearanceAnchor {
    Eigen::Vector3d center_world = Eigen::Vector3d::Zero(), axis_world = Eigen::Vector3d::Zero();
    double value_m = 0.0;
  } clearance_anchor_;
  bool clearance_start_bounded_ = false;
  std::vector<plane_contact_detail::EventValues> looks_;  // within a step, the last is its end's
  mutable SegmentRing segments_;  // dense output is computed when first sampled
  std::optional<PendingEvent> pending_;
  double reached_ = 0.0;       // time of the last outcome
  double window_start_ = 0.0;  // state_at covers [window_start_, reached_]
  double last_event_time_ = -std::numeric_limits<double>::infinity();
  int events_at_instant_ = 0;
  std::optional<Finished> finished_;
  std::optional<PlaneContactOutcome> initial_outcome_;
};

}  // namespace virtual_go
