// One stone's current flight in the world (docs/physics.md, "World"): the state and time it began
// at (its closed form's anchor), the exact integrator's per-stone cache that makes sampling on a
// fixed grid two quaternion products per sample, and the flight's first contact, searched once
// per flight up to a horizon and extended only when the flight outlives it. Sampling never
// touches the search, and the search never changes the flight.
#pragma once

#include <limits>
#include <optional>

#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/contact/time_of_impact.h"
#include "virtual_go/flight/flight_cache.h"
#include "virtual_go/flight/integrator.h"

namespace virtual_go {

class FlightTrack {
 public:
  // A new flight from `state` at t_s: the integrator's cache is invalidated, nothing is known
  // about contacts yet.
  void begin(const RigidBodyState& state, double t_s);

  const RigidBodyState& anchor() const { return anchor_; }
  double anchor_time_s() const { return anchor_time_; }

  // Moves `state`, this flight's state at state_time_s, to t_s > state_time_s with one step of
  // the exact integrator and this flight's cache. Steps of the same length (a fixed grid) reuse
  // the cache's two step rotations; a step whose length differs from the cached one only by the
  // round-off of the grid times (the integrator's own time stays within 1e-14 s of t_s) counts
  // as the same. Returns false (state untouched) when t_s <= state_time_s.
  bool sample(const Integrator& exact, RigidBodyState& state, double state_time_s, double t_s);

  // The contact search. `contact()` is the flight's first contact once found; until then the
  // flight is known to be contact-free up to clear_until_s().
  void record_search(const TimeOfImpact& result);
  const std::optional<TimeOfImpact>& contact() const { return contact_; }
  double clear_until_s() const { return clear_until_; }
  // Up to when advancing needs no work beyond sampling: the contact time (exclusive) or the end
  // of the known contact-free time (inclusive).
  double contact_time_s() const {
    return contact_ ? contact_->time_s : std::numeric_limits<double>::infinity();
  }
  // Without a board there is nothing to search: the flight is free forever.
  void set_free_forever() { clear_until_ = std::numeric_limits<double>::infinity(); }

 private:
  RigidBodyState anchor_;
  double anchor_time_ = 0.0;
  FlightCache cache_;
  double cache_anchor_time_ = 0.0;  // time of the state the integrator anchored its cache at
  std::optional<TimeOfImpact> contact_;
  double clear_until_ = -std::numeric_limits<double>::infinity();
};

}  // namespace virtual_go
