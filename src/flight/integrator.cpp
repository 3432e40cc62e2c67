#include "virtual_go/flight/integrator.h"

#include <cmath>
#include <limits>

#include "virtual_go/common/validation.h"
#include "virtual_go/flight/flight_cache.h"
#include "virtual_go/flight/free_flight.h"
#include "virtual_go/flight/integrator_registry.h"

namespace virtual_go {
namespace {

// On the hot path of every step: x * 0 is 0 for finite x and NaN for inf or NaN, so one sum
// tests all 13 numbers without a branch each (Eigen's allFinite() costs about 4x more here).
bool all_finite(const RigidBodyState& s) {
  const double zero = (s.position_world * 0.0).sum() + (s.velocity_world * 0.0).sum() +
                      (s.orientation.coeffs() * 0.0).sum() + (s.angular_momentum_world * 0.0).sum();
  return zero == 0.0;
}

}  // namespace

Integrator::Integrator(const IntegratorInfo& info, const MotionSetup& setup)
    : info_(&info), setup_(setup), has_gravity_(!setup.gravity_world.isZero(0.0)) {
  require_finite("gravity", setup.gravity_world);
}

const std::string& Integrator::name() const { return info_->name; }

double Integrator::max_rotation_per_step() const { return info_->max_rotation_per_step; }

void Integrator::advance(RigidBodyState& state, double dt_s, FlightCache& cache) const {
  if (!(dt_s > 0.0 && dt_s <= std::numeric_limits<double>::max())) require_positive("dt", dt_s);
  // Check the input before stepping: a zero quaternion would otherwise pass through a step
  // unchanged (normalising zero leaves zero) and come out finite, and a huge one (|q| ~ 1e300)
  // overflows Eigen's normalize() into zero. The cheap test runs every step; validated() only
  // runs for a non-finite or non-unit input, to reject it or to normalise it.
  RigidBodyState next = state;
  if (!all_finite(state) || !(std::abs(state.orientation.coeffs().squaredNorm() - 1.0) <= 1e-12)) {
    next = state.validated();
    // Every step's output is unit: a state that needed normalising was not one, so whatever
    // the cache holds for this body cannot continue it.
    cache.invalidate();
  }
  try {
    step(next, dt_s, cache);
  } catch (...) {
    cache.invalidate();  // the cache may have moved on; the state has not
    throw;
  }
  if (!all_finite(next)) {
    cache.invalidate();
    state.validated();  // names the bad input field, if the input was the cause
    throw IntegrationError(name() + ": step of dt " + format_value(dt_s) +
                           " s produced a non-finite state");
  }
  state = next;
}

void Integrator::advance(RigidBodyState& state, double dt_s) const {
  FlightCache fresh;
  advance(state, dt_s, fresh);
}

void Integrator::translate_exact(RigidBodyState& state, double dt_s) const {
  free_flight(state, setup_.gravity_world, has_gravity_, dt_s, state);
}

}  // namespace virtual_go
