#include "virtual_go/world/flight_track.h"

#include <cmath>

namespace virtual_go {
namespace {

// The exact integrator's time (anchor + n dt) may differ from the requested grid time by this
// much (s) before the cache is re-anchored: 1e-14 s moves a stone at 10 m/s by 1e-13 m.
constexpr double kGridTimeSlackS = 1e-14;

}  // namespace

void FlightTrack::begin(const RigidBodyState& state, double t_s) {
  anchor_ = state;
  anchor_time_ = t_s;
  cache_.invalidate();
  contact_.reset();
  clear_until_ = t_s;
}

bool FlightTrack::sample(const Integrator& exact, RigidBodyState& state, double state_time_s,
                         double t_s) {
  double dt = t_s - state_time_s;
  if (!(dt > 0.0)) return false;
  ExactStepCache& c = cache_.exact();
  if (cache_.holds_anchor() && dt != c.dt_s) {
    // Grid times carry round-off: t_(n+1) - t_n is not the same double for every n. Keep the
    // cached step while the integrator's own time stays on the requested one.
    const double integrator_time =
        cache_anchor_time_ + static_cast<double>(c.steps_since_anchor + 1) * c.dt_s;
    if (std::abs(integrator_time - t_s) <= kGridTimeSlackS) dt = c.dt_s;
  }
  if (!cache_.holds_anchor() || dt != c.dt_s) cache_anchor_time_ = state_time_s;
  exact.advance(state, dt, cache_);
  return true;
}

void FlightTrack::record_search(const TimeOfImpact& result) {
  if (result.hit) {
    contact_ = result;
  } else {
    clear_until_ = result.time_s;
  }
}

}  // namespace virtual_go
