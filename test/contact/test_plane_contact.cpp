// Sustained contact of a size-33 slate stone on a plane, against physics: closed forms (sliding
// with rotation frozen, small rocking periods, spin decay, rim rolling in place, leaving the
// board, lift-off on the rim), energy-integral quadratures (rocking periods at any amplitude,
// across the cap/rim switch), an independent planar model integrated in the test (a sliding
// stone pitching, rocking with rolling resistance, slip and stick), conservation (Jellett's
// integral, energy), and exactness (gap 0 in every sampled state, energy never above an earlier
// state's, exact and free rest).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <functional>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "plane_contact_reference.h"
#include "virtual_go/body/mass_properties.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/contact/plane_contact.h"
#include "virtual_go/go/board.h"

namespace vg = virtual_go;
namespace ref = plane_contact_reference;
using Eigen::Quaterniond;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

const vg::LensShape kShape(0.022, 0.0092);  // size 33
const vg::MassProperties kMass = vg::MassProperties::of_lens(kShape, 2700.0);
const vg::LensGeometry kLens(kShape);
const double kG = 9.80665;
const Vector3d kGravity(0, 0, -kG);
const double kM = kMass.mass();
const double kI1 = kMass.principal_moments_body().x();
const double kI3 = kMass.principal_moments_body().z();
const double kA = 0.011, kC = 0.0046;
const double kR = (kA * kA + kC * kC) / (2 * kC), kD = kR - kC;
const double kDeg = M_PI / 180;

vg::MotionModel stone_model() { return vg::MotionModel(vg::MotionModelKind::rigid_body, kMass); }

// A stone whose rotation is practically frozen: the same mass, moments 10^6 kg m^2.
vg::MotionModel frozen_rotation_model() {
  return vg::MotionModel(vg::MotionModelKind::rigid_body,
                         vg::MassProperties(kM, Vector3d(1e6, 1e6, 1e6)));
}

vg::ContactMaterial material(double mu, double l_r, double l_s) {
  vg::ContactMaterial m;
  m.friction = mu;
  m.rolling_resistance_m = l_r;
  m.spinning_friction_m = l_s;
  return m;
}

// The lowest lens point relative to G (world), from the lens' support function.
Vector3d lowest_offset(const Quaterniond& q) {
  return q * kLens.support_body(q.conjugate() * Vector3d(0, 0, -1));
}

// A state touching the plane z = h0 with orientation q: z_G and v_z from the lowest point, so
// that its normal velocity is zero.
vg::RigidBodyState on_plane(const vg::MotionModel& model, const Quaterniond& q, const Vector2d& xy,
                            const Vector2d& v_xy, const Vector3d& omega, double h0 = 0.0) {
  const Vector3d r = lowest_offset(q);
  vg::RigidBodyState s;
  s.orientation = q;
  s.position_world = Vector3d(xy.x(), xy.y(), h0 - r.z());
  s.velocity_world = Vector3d(v_xy.x(), v_xy.y(), -omega.cross(r).z());
  s.angular_momentum_world = model.angular_momentum_world(q, omega);
  return s;
}

Quaterniond tilt_about_y(double theta) {
  return Quaterniond(Eigen::AngleAxisd(theta, Vector3d::UnitY()));
}

double tilt_of(const vg::RigidBodyState& s) {
  const Vector3d b = s.orientation * Vector3d::UnitZ();
  return std::atan2(b.x(), b.z());
}

Vector3d omega_of(const vg::MotionModel& model, const vg::RigidBodyState& s) {
  return model.angular_velocity_world(s.orientation, s.angular_momentum_world);
}

double energy_of(const vg::MotionModel& model, const vg::RigidBodyState& s) {
  return 0.5 * model.mass_properties().mass() * s.velocity_world.squaredNorm() +
         0.5 * omega_of(model, s).dot(s.angular_momentum_world) -
         model.mass_properties().mass() * kGravity.dot(s.position_world);
}

// Gap between the lowest lens point and the plane.
double gap_of(const vg::RigidBodyState& s, double h0) {
  return s.position_world.z() + lowest_offset(s.orientation).z() - h0;
}

// Samples a phase on a time grid (advance to each grid time, stopping at events), checking on
// the way what must hold in every state: gap 0, energy never above an earlier state's, unit
// quaternion, finite values.
struct Trace {
  std::vector<double> t;
  std::vector<vg::RigidBodyState> s;
  std::vector<vg::PlaneContactOutcome> events;
  double worst_gap = 0;
  // Largest energy above the phase's starting energy (must be <= 0), and largest rise of a state's
  // energy over the lowest energy of the earlier ones, relative to m g a + |E|: within one
  // integrator step the dense output's energy error (~1e-13) is not guarded.
  double worst_energy_above_start = -1, worst_energy_rise_relative = 0;
  double energy_scale = 0;  // |E| + m g a, J
  vg::PlaneContactOutcome last;
};

Trace trace(vg::PlaneContact& phase, const vg::MotionModel& model, double t_end, double dt,
            double h0 = 0.0, const std::function<void(double, double)>& between = nullptr) {
  Trace out;
  double e_previous = energy_of(model, phase.state_at(phase.time_reached()));
  const double e_start = e_previous;
  const double e_scale = std::abs(e_previous) + kM * kG * kA;
  out.energy_scale = e_scale;
  double t = phase.time_reached();
  double grid = t;
  for (int iteration = 0;; ++iteration) {
    if (iteration > 1000000) {
      ADD_FAILURE() << "trace does not advance beyond t = " << t;
      break;
    }
    const double target = std::min(grid + dt, t_end);
    const vg::PlaneContactOutcome o = phase.advance(target);
    const double t_before = t;
    t = o.time_s;
    if (between) between(t_before, t);
    EXPECT_TRUE(o.state.position_world.allFinite());
    EXPECT_NEAR(o.state.orientation.norm(), 1.0, 1e-15);
    out.worst_gap = std::max(out.worst_gap, std::abs(gap_of(o.state, h0)));
    const double e = energy_of(model, o.state);
    out.worst_energy_above_start = std::max(out.worst_energy_above_start, e - e_start);
    out.worst_energy_rise_relative =
        std::max(out.worst_energy_rise_relative, (e - e_previous) / e_scale);
    e_previous = std::min(e_previous, e);
    out.t.push_back(t);
    out.s.push_back(o.state);
    out.last = o;
    if (o.event != vg::PlaneContactEvent::none) out.events.push_back(o);
    if (o.finished || t >= t_end) break;
    if (o.event == vg::PlaneContactEvent::none) grid = target;
  }
  return out;
}

// Zero crossings (upward and downward) of f(state) within the run, refined by bisection on
// state_at inside each advance window; returns (time, state there).
struct Crossing {
  double t;
  vg::RigidBodyState s;
};
std::vector<Crossing> crossings(vg::PlaneContact& phase, const vg::MotionModel& model, double t_end,
                                double dt,
                                const std::function<double(const vg::RigidBodyState&)>& f,
                                Trace* record = nullptr, double h0 = 0.0) {
  std::vector<Crossing> out;
  double f_prev = f(phase.state_at(phase.time_reached()));
  Trace r = trace(phase, model, t_end, dt, h0, [&](double t0, double t1) {
    const double f1 = f(phase.state_at(t1));
    if ((f_prev < 0) != (f1 < 0) && t1 > t0) {
      double lo = t0, hi = t1, f_lo = f_prev;
      for (int i = 0; i < 200 && hi - lo > 1e-14; ++i) {
        const double mid = 0.5 * (lo + hi);
        const double fm = f(phase.state_at(mid));
        if ((fm < 0) == (f_lo < 0)) {
          lo = mid;
          f_lo = fm;
        } else {
          hi = mid;
        }
      }
      out.push_back({0.5 * (lo + hi), phase.state_at(0.5 * (lo + hi))});
    }
    f_prev = f1;
  });
  if (record) *record = r;
  return out;
}

void expect_energy_never_rises(const Trace& r) {
  EXPECT_LE(r.worst_energy_above_start, 1e-14 * r.energy_scale);  // round-off of E itself
  EXPECT_LT(r.worst_energy_rise_relative, 1e-11);  // the dense output's interpolation error
}

void report_cost(const std::string& what, const vg::PlaneContactCounters& c, double seconds) {
  std::cout << "[ cost     ] " << what << ": " << c.steps / seconds << " steps/s, "
            << c.rhs_evaluations / seconds << " rhs/s, " << c.extra_solves / seconds
            << " extra solves/s, " << c.events << " events, " << c.energy_guard_scalings
            << " energy-guard scalings over " << seconds << " s\n";
  ::testing::Test::RecordProperty(what + "_steps_per_s", std::to_string(c.steps / seconds));
  ::testing::Test::RecordProperty(what + "_rhs_per_s", std::to_string(c.rhs_evaluations / seconds));
}

void report(const std::string& what, double value) {
  std::cout << "[ measured ] " << what << " = " << value << "\n";
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Sliding

TEST(PlaneContact, SlideWithRotationFrozenStopsAtTheTextbookDistanceAndTime) {
  // s = v0^2 / (2 mu g) = 42.488176 mm, t = v0 / (mu g) = 169.9527 ms (mu 0.3, v0 0.5 m/s).
  const double mu = 0.3, v0 = 0.5;
  EXPECT_NEAR(v0 * v0 / (2 * mu * kG), 42.488176e-3, 1e-9);
  EXPECT_NEAR(v0 / (mu * kG), 169.9527e-3, 1e-7);
  const auto model = frozen_rotation_model();
  for (const Vector2d& direction : {Vector2d(1, 0), Vector2d(0.6, -0.8)}) {
    const Vector2d x0(0.01, 0.02);
    vg::PlaneContact phase(
        model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(), material(mu, 0, 0),
        on_plane(model, Quaterniond::Identity(), x0, v0 * direction, Vector3d::Zero()), 0.0);
    const Trace r = trace(phase, model, 1.0, 0.01);
    ASSERT_FALSE(r.events.empty());
    const auto& stop = r.events.back();
    EXPECT_EQ(stop.event, vg::PlaneContactEvent::rest);  // nothing turns: the stop is rest
    EXPECT_NEAR(stop.time_s, v0 / (mu * kG), 1e-12);
    const Vector2d travelled = stop.state.position_world.head<2>() - x0;
    EXPECT_NEAR(travelled.norm(), v0 * v0 / (2 * mu * kG), 1e-12);
    EXPECT_NEAR(travelled.normalized().dot(direction), 1.0, 1e-15);
    EXPECT_EQ(stop.state.velocity_world, Vector3d::Zero());
    EXPECT_EQ(stop.state.angular_momentum_world, Vector3d::Zero());
    // Uniform deceleration in between: x(t) = v0 t - mu g t^2 / 2.
    for (std::size_t i = 0; i < r.t.size(); ++i) {
      const double t = r.t[i];
      if (t >= stop.time_s) break;
      EXPECT_NEAR((r.s[i].position_world.head<2>() - x0).norm(), v0 * t - 0.5 * mu * kG * t * t,
                  1e-12);
    }
    EXPECT_LT(r.worst_gap, 1e-17);
    expect_energy_never_rises(r);
    report("frozen slide: stop time error (s)", stop.time_s - v0 / (mu * kG));
    report("frozen slide: distance error (m)", travelled.norm() - v0 * v0 / (2 * mu * kG));
  }
}

TEST(PlaneContact, FreeLensSlidingPitchesAndStopsAsThePlanarModelSays) {
  // 0.5 m/s, mu 0.3, flat start, no couples: friction acts c below G and pitches the stone
  // forward; slip ends, then it rolls (rocks) without slipping.
  const double mu = 0.3, v0 = 0.5;
  const auto model = stone_model();
  vg::PlaneContact phase(
      model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(), material(mu, 0, 0),
      on_plane(model, Quaterniond::Identity(), Vector2d::Zero(), Vector2d(v0, 0), Vector3d::Zero()),
      0.0);
  // The reference: the planar model, RK4 with 2 us steps.
  const ref::PlanarCap planar(kM, kI1, kR, kD, kG, mu, 0.0);
  ref::PlanarCap::Mode mode;
  double ref_max_pitch = 0, ref_rock_amplitude = 0;
  std::vector<std::pair<double, double>> ref_tilt;
  const auto ref_events = planar.run({0, 0, v0, 0}, mode, 0.6, 2e-6, [&](double t, const auto& s) {
    ref_tilt.emplace_back(t, s.theta);
  });
  ASSERT_GE(ref_events.size(), 1u);
  const auto& ref_stop = ref_events.front();
  for (const auto& [t, theta] : ref_tilt) {
    (t <= ref_stop.time ? ref_max_pitch : ref_rock_amplitude) =
        std::max(t <= ref_stop.time ? ref_max_pitch : ref_rock_amplitude, std::abs(theta));
  }
  // Reference values computed independently (scipy): slip ends 182.729 ms at 42.2397 mm.
  EXPECT_NEAR(ref_stop.time, 182.729e-3, 1e-6);

  double max_pitch = 0;
  const Trace r = trace(phase, model, 0.6, 0.5e-3);
  ASSERT_FALSE(r.events.empty());
  EXPECT_EQ(r.events.front().event, vg::PlaneContactEvent::slip_stop);
  const auto& stop = r.events.front();
  for (std::size_t i = 0; i < r.t.size() && r.t[i] <= stop.time_s; ++i) {
    max_pitch = std::max(max_pitch, std::abs(tilt_of(r.s[i])));
  }
  double rock_amplitude = 0;
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    if (r.t[i] > stop.time_s) rock_amplitude = std::max(rock_amplitude, std::abs(tilt_of(r.s[i])));
  }
  EXPECT_NEAR(stop.time_s, ref_stop.time, 1e-11);
  EXPECT_NEAR(stop.state.position_world.x(), ref_stop.state.x, 1e-12);
  EXPECT_NEAR(tilt_of(stop.state), ref_stop.state.theta, 1e-10);
  EXPECT_NEAR(stop.state.position_world.x(), 42.2397e-3, 1e-7);
  // Pitch: max about 15.5 deg while sliding, rocking about 10.14 deg after (sampled every 0.5 ms).
  EXPECT_NEAR(max_pitch, ref_max_pitch, 2e-4);
  EXPECT_NEAR(max_pitch / kDeg, 15.5, 0.05);
  EXPECT_NEAR(rock_amplitude, ref_rock_amplitude, 2e-4);
  EXPECT_NEAR(rock_amplitude / kDeg, 10.14, 0.01);
  // Rolling without slip conserves energy after the stop.
  const double e_stop = energy_of(model, stop.state);
  double worst = 0;
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    if (r.t[i] > stop.time_s) worst = std::max(worst, std::abs(energy_of(model, r.s[i]) - e_stop));
  }
  EXPECT_LT(worst / e_stop, 1e-11);
  EXPECT_LT(r.worst_gap, 1e-17);
  expect_energy_never_rises(r);
  report("free slide: slip end (s)", stop.time_s);
  report("free slide: slip end - planar reference (s)", stop.time_s - ref_stop.time);
  report("free slide: x_G at slip end (m)", stop.state.position_world.x());
  report("free slide: max pitch while sliding (deg)", max_pitch / kDeg);
  report("free slide: rocking amplitude after (deg)", rock_amplitude / kDeg);
  report("free slide: rolling energy drift (relative)", worst / e_stop);
}

// ---------------------------------------------------------------------------------------------
// Rocking

namespace {

double rolling_inertia(double theta) {  // I1 + m |r|^2 about the contact point
  return kI1 + kM * (kD * kD - 2 * kD * kR * std::cos(theta) + kR * kR);
}
// V(theta0) - V(theta) on the cap, m g d (cos(theta) - cos(theta0)), without cancellation.
double cap_drop(double theta0, double theta, double difference) {
  return 2 * kM * kG * kD * std::sin(0.5 * difference) * std::sin(0.5 * (theta0 + theta));
}

// The measured period: mean spacing of every second zero crossing of the tilt.
double measured_period(const std::vector<Crossing>& zeros) {
  const std::size_t n = zeros.size();
  EXPECT_GE(n, 3u);
  const std::size_t first = (n - 1) % 2;  // an even number of half periods to the last
  return (zeros[n - 1].t - zeros[first].t) / ((n - 1 - first) / 2);
}

}  // namespace

TEST(PlaneContact, SmallRockingPeriodsRollingAndFrictionless) {
  const auto model = stone_model();
  // Closed forms (small amplitude): 130.092 ms rolling, 95.260 ms frictionless.
  const double t_rolling = 2 * M_PI * std::sqrt((kI1 + kM * kC * kC) / (kM * kG * kD));
  const double t_frictionless = 2 * M_PI * std::sqrt(kI1 / (kM * kG * kD));
  EXPECT_NEAR(t_rolling, 130.092e-3, 1e-6);
  EXPECT_NEAR(t_frictionless, 95.260e-3, 1e-6);
  for (double mu : {0.3, 0.0}) {
    for (double theta0 : {0.25 * kDeg, 5 * kDeg}) {
      vg::PlaneContact phase(model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(),
                             material(mu, 0, 0),
                             on_plane(model, tilt_about_y(theta0), Vector2d::Zero(),
                                      Vector2d::Zero(), Vector3d::Zero()),
                             0.0);
      Trace r;
      const auto zeros = crossings(
          phase, model, 0.7, 1e-3, [](const vg::RigidBodyState& s) { return tilt_of(s); }, &r);
      const double period = measured_period(zeros);
      // Exact period of the rigid model at this amplitude: the energy integral.
      const double exact = mu > 0 ? ref::oscillation_period(rolling_inertia, cap_drop, theta0)
                                  : ref::oscillation_period(
                                        [](double th) {
                                          const double s = kD * std::sin(th);
                                          return kI1 + kM * s * s;
                                        },
                                        cap_drop, theta0);
      EXPECT_NEAR(period, exact, 1e-11 * exact) << mu << " " << theta0;
      if (theta0 < kDeg) {
        EXPECT_NEAR(period, mu > 0 ? t_rolling : t_frictionless, 3e-6);
        if (mu > 0) {
          EXPECT_NEAR(period, 130.094e-3, 1e-6);  // reference value at 0.25 deg
        }
      }
      EXPECT_TRUE(r.events.empty());  // no mode change: it rocks forever
      EXPECT_LT(r.worst_gap, 1e-17);
      expect_energy_never_rises(r);
      // Frictionless: G does not move sideways.
      if (mu == 0) {
        for (const auto& s : r.s) EXPECT_NEAR(s.position_world.x(), 0.0, 1e-15);
      }
      const std::string name = std::string(mu > 0 ? "rolling" : "frictionless") + " rocking at " +
                               std::to_string(theta0 / kDeg) + " deg";
      report(name + ": period (s)", period);
      report(name + ": period - energy integral (s)", period - exact);
      if (theta0 > kDeg && mu > 0) report_cost("rocking (rolling, 5 deg)", phase.counters(), 0.7);
    }
  }
}

TEST(PlaneContact, RockingWithRollingResistanceDecaysLinearlyAndComesToExactRest) {
  // Coulomb-type rolling couple l_r N: amplitude falls by 2 l_r / d per half cycle (0.0211 deg
  // for l_r 2 um); rest in finite time with a residual tilt <= l_r / d.
  const double l_r = 2e-6, theta0 = 0.3 * kDeg;
  EXPECT_NEAR(2 * l_r / kD / kDeg, 0.0211, 1e-4);
  const auto model = stone_model();
  vg::PlaneContact phase(
      model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(), material(0.3, l_r, 0.0),
      on_plane(model, tilt_about_y(theta0), Vector2d::Zero(), Vector2d::Zero(), Vector3d::Zero()),
      0.0);
  // Turning points: zeros of the rocking rate omega_y.
  Trace r;
  const auto turns = crossings(
      phase, model, 3.0, 1e-3, [&](const vg::RigidBodyState& s) { return omega_of(model, s).y(); },
      &r);
  ASSERT_EQ(r.last.event, vg::PlaneContactEvent::rest);
  const double rest_time = r.last.time_s;
  // The planar reference with the same law.
  const ref::PlanarCap planar(kM, kI1, kR, kD, kG, 0.3, l_r);
  ref::PlanarCap::Mode mode;
  mode.tangential = ref::PlanarCap::Tangential::stick;
  mode.rolling = ref::PlanarCap::Rolling::stuck;
  mode = planar.choose({0, theta0, 0, 0}, mode, false, false);
  const auto ref_events =
      planar.run({0, theta0, 0, 0}, mode, 3.0, 1e-5, [](double, const auto&) {});
  std::vector<double> ref_amplitudes{theta0};
  for (const auto& e : ref_events) ref_amplitudes.push_back(std::abs(e.state.theta));
  // Amplitudes at the turning points: the initial tilt, then every turn.
  std::vector<double> amplitudes{theta0};
  for (const auto& turn : turns) {
    // Skip the start (released from rest) and the final stop (which is the rest event).
    if (turn.t > 1e-6 && turn.t < rest_time - 1e-9) amplitudes.push_back(std::abs(tilt_of(turn.s)));
  }
  amplitudes.push_back(std::abs(tilt_of(r.last.state)));  // the last turn is the rest
  // Half-cycle decrements from the reference turning points and ours (events at the turns).
  const double decrement = 2 * l_r / kD;
  const int half_cycles = static_cast<int>(amplitudes.size()) - 1;
  ASSERT_EQ(amplitudes.size(), ref_amplitudes.size());
  double worst_decrement_error = 0, worst_vs_reference = 0;
  for (std::size_t i = 1; i < amplitudes.size(); ++i) {
    worst_vs_reference = std::max(worst_vs_reference, std::abs(amplitudes[i] - ref_amplitudes[i]));
    if (i + 1 == amplitudes.size()) break;  // the last half cycle ends at rest, short of a turn
    const double dec = amplitudes[i - 1] - amplitudes[i];
    worst_decrement_error = std::max(worst_decrement_error, std::abs(dec - decrement) / decrement);
  }
  EXPECT_LT(worst_decrement_error, 2e-3);
  EXPECT_LT(worst_vs_reference, 1e-11);
  // Ours against the reference: the rest time, the final tilt, and the number of half cycles.
  EXPECT_NEAR(rest_time, ref_events.back().time, 1e-10);
  EXPECT_NEAR(tilt_of(r.last.state), ref_events.back().state.theta, 1e-11);
  EXPECT_LE(std::abs(tilt_of(r.last.state)), l_r / kD);
  // Rest is exact: velocities exactly 0, and frozen bit for bit without any work.
  EXPECT_EQ(r.last.state.velocity_world, Vector3d::Zero());
  EXPECT_EQ(r.last.state.angular_momentum_world, Vector3d::Zero());
  const vg::PlaneContactCounters before = phase.counters();
  const vg::RigidBodyState frozen = r.last.state;
  double t = rest_time;
  for (int i = 0; i < 1000000; ++i) {
    t += 1e-3;
    const auto o = phase.advance(t);
    if (!(o.state == frozen) || !o.finished) {
      ADD_FAILURE() << "rest state changed at step " << i;
      break;
    }
  }
  EXPECT_EQ(phase.counters().steps, before.steps);
  EXPECT_EQ(phase.counters().rhs_evaluations, before.rhs_evaluations);
  EXPECT_EQ(phase.counters().extra_solves, before.extra_solves);
  EXPECT_LT(r.worst_gap, 1e-17);
  expect_energy_never_rises(r);
  report("rolling resistance: half cycles to rest", half_cycles);
  report("rolling resistance: worst decrement vs 2 l_r/d (relative)", worst_decrement_error);
  report("rolling resistance: worst turning amplitude - planar reference (rad)",
         worst_vs_reference);
  report("rolling resistance: rest time (s)", rest_time);
  report("rolling resistance: rest time - planar reference (s)",
         rest_time - ref_events.back().time);
  report("rolling resistance: residual tilt / (l_r/d)",
         std::abs(tilt_of(r.last.state)) / (l_r / kD));
}

// ---------------------------------------------------------------------------------------------
// Spinning and rim rolling

TEST(PlaneContact, SpinOnTheFaceStopsLinearlyAtTheExactTime) {
  // omega(t) = omega0 - l_s m g t / I3, stops at I3 omega0 / (l_s m g), then exact rest.
  const double l_s = 15e-6, omega0 = 10.0;
  const double stop = kI3 * omega0 / (l_s * kM * kG);
  const auto model = stone_model();
  vg::PlaneContact phase(model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(),
                         material(0.3, 5e-6, l_s),
                         on_plane(model, Quaterniond::Identity(), Vector2d(0.03, 0.04),
                                  Vector2d::Zero(), Vector3d(0, 0, omega0)),
                         0.0);
  const Trace r = trace(phase, model, stop + 1.0, 0.05);
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.last.event, vg::PlaneContactEvent::rest);
  EXPECT_NEAR(r.last.time_s, stop, 1e-12 * stop);
  double worst = 0;
  for (std::size_t i = 0; i + 1 < r.t.size(); ++i) {
    const double expected = omega0 - l_s * kM * kG * r.t[i] / kI3;
    worst = std::max(worst, std::abs(omega_of(model, r.s[i]).z() - expected) / omega0);
    EXPECT_NEAR(r.s[i].position_world.x(), 0.03, 1e-15);
  }
  EXPECT_LT(worst, 1e-10);
  expect_energy_never_rises(r);
  report("spin: stop time (s)", r.last.time_s);
  report("spin: stop time - I3 w0/(l_s m g) (s)", r.last.time_s - stop);
  report("spin: worst |omega - linear| / omega0", worst);
  report_cost("spinning flat (10 rad/s)", phase.counters(), r.last.time_s);
}

TEST(PlaneContact, FlatSlideAndSpinDownWithRollingHeldIsExactAndCostsOneStepPerStop) {
  // Flat on its face with a rolling resistance that holds the friction's couple (l_r >= mu c):
  // G slides in a straight line at mu g and stops at v0 / (mu g) after v0^2 / (2 mu g), the spin
  // falls at l_s m g / I3 and stops at I3 w0 / (l_s m g), then exact rest. Checked against those
  // closed forms, against an independent integration (Boost.Odeint, Dormand-Prince 5) of the
  // same Newton-Euler equations, and against the core's integrator on the same stone tilted by
  // 1e-7 rad (no closed form there: the axis is not vertical).
  const double mu = 0.3, l_r = 0.01, l_s = 15e-6, v0 = 0.3, w0 = 15.0;
  const Vector2d dir(0.6, 0.8), xy0(0.01, 0.02);
  const double slip_stop = v0 / (mu * kG), spin_stop = kI3 * w0 / (l_s * kM * kG);
  const auto model = stone_model();
  auto make = [&](double tilt) {
    return vg::PlaneContact(
        model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(), material(mu, l_r, l_s),
        on_plane(model, tilt_about_y(tilt), xy0, v0 * dir, Vector3d(0, 0, w0)), 0.0);
  };
  vg::PlaneContact flat = make(0.0);
  const Trace r = trace(flat, model, spin_stop + 1.0, 0.01);
  ASSERT_EQ(r.events.size(), 2u);
  EXPECT_EQ(r.events[0].event, vg::PlaneContactEvent::slip_stop);
  EXPECT_NEAR(r.events[0].time_s, slip_stop, 1e-15);
  EXPECT_EQ(r.last.event, vg::PlaneContactEvent::rest);
  EXPECT_NEAR(r.last.time_s, spin_stop, 1e-12 * spin_stop);
  const Vector2d x_end = xy0 + v0 * v0 / (2 * mu * kG) * dir;
  EXPECT_NEAR((r.last.state.position_world.head<2>() - x_end).norm(), 0.0, 1e-15);
  EXPECT_EQ(r.last.state.velocity_world.norm(), 0.0);
  expect_energy_never_rises(r);
  EXPECT_LE(flat.counters().steps, 3);  // one closed-form piece per stop
  EXPECT_EQ(flat.counters().rhs_evaluations, 0);

  // Odeint on (x, y, v_x, v_y, omega_z, psi) up to just before the slip stops.
  using OdeState = std::array<double, 6>;
  auto newton_euler = [&](const OdeState& y, OdeState& dy, double /*t*/) {
    const double speed = std::hypot(y[2], y[3]);
    dy[0] = y[2];
    dy[1] = y[3];
    dy[2] = -mu * kG * y[2] / speed;
    dy[3] = -mu * kG * y[3] / speed;
    dy[4] = -(y[4] > 0 ? 1.0 : -1.0) * l_s * kM * kG / kI3;
    dy[5] = y[4];
  };
  OdeState y{xy0.x(), xy0.y(), v0 * dir.x(), v0 * dir.y(), w0, 0.0};
  const double t_check = 0.9 * slip_stop;
  boost::numeric::odeint::integrate_adaptive(
      boost::numeric::odeint::make_controlled<boost::numeric::odeint::runge_kutta_dopri5<OdeState>>(
          1e-13, 1e-13),
      newton_euler, y, 0.0, t_check, 1e-4);
  vg::PlaneContact flat_again = make(0.0);
  flat_again.advance(t_check);
  const vg::RigidBodyState s = flat_again.state_at(t_check);
  EXPECT_NEAR(s.position_world.x(), y[0], 1e-12);
  EXPECT_NEAR(s.position_world.y(), y[1], 1e-12);
  EXPECT_NEAR(s.velocity_world.x(), y[2], 1e-11);
  EXPECT_NEAR(s.velocity_world.y(), y[3], 1e-11);
  EXPECT_NEAR(omega_of(model, s).z(), y[4], 1e-10);
  const Vector3d e_x = s.orientation * Vector3d::UnitX();
  EXPECT_NEAR(std::remainder(std::atan2(e_x.y(), e_x.x()) - y[5], 2 * M_PI), 0.0, 1e-10);

  // The integrator on the stone tilted by 1e-7 rad: the same motion to O(1e-7).
  vg::PlaneContact tilted = make(1e-7);
  const Trace rt = trace(tilted, model, spin_stop + 1.0, 0.01);
  ASSERT_GE(rt.events.size(), 2u);
  EXPECT_EQ(rt.events[0].event, vg::PlaneContactEvent::slip_stop);
  EXPECT_NEAR(rt.events[0].time_s, slip_stop, 1e-6 * slip_stop);
  EXPECT_EQ(rt.last.event, vg::PlaneContactEvent::rest);
  EXPECT_NEAR(rt.last.time_s, spin_stop, 1e-6 * spin_stop);
  EXPECT_NEAR((rt.last.state.position_world.head<2>() - x_end).norm(), 0.0, 1e-8);
  report("flat slide+spin: slip stop - v0/(mu g) (s)", r.events[0].time_s - slip_stop);
  report("flat slide+spin: rest - I3 w0/(l_s m g) (s)", r.last.time_s - spin_stop);
  report("flat slide+spin: tilted 1e-7 (integrated) rest - closed form (s)",
         rt.last.time_s - r.last.time_s);
  report_cost("flat slide+spin, closed form", flat.counters(), r.last.time_s);
  report_cost("flat slide+spin tilted 1e-7, integrated", tilted.counters(), rt.last.time_s);
}

TEST(PlaneContact, RimRollingInPlaceKeepsTheCentreFixedAndTheEnergy) {
  // Omega^2 sin(alpha) = m g a / I1: 67.567078 rad/s at 75 deg, 71.357842 at 60, 75.871740 at 50.
  const auto model = stone_model();
  const std::pair<double, double> cases[] = {{75, 67.567078}, {60, 71.357842}, {50, 75.871740}};
  for (const auto& [alpha_deg, table] : cases) {
    const double alpha = alpha_deg * kDeg;
    const double rate = std::sqrt(kM * kG * kA / (kI1 * std::sin(alpha)));
    EXPECT_NEAR(rate, table, 2e-6);
    const Quaterniond q = tilt_about_y(alpha);
    const Vector3d b = q * Vector3d::UnitZ();
    const Vector3d omega = rate * (Vector3d::UnitZ() - std::cos(alpha) * b);
    const auto start = on_plane(model, q, Vector2d::Zero(), Vector2d::Zero(), omega);
    vg::PlaneContact phase(model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(),
                           material(0.9, 0, 0), start, 0.0);
    EXPECT_EQ(phase.mode().part, vg::LensPart::rim);
    const double turns = 3, t_end = turns * 2 * M_PI / rate;
    const Trace r = trace(phase, model, t_end, 1e-3);
    EXPECT_TRUE(r.events.empty());
    double worst_centre = 0, worst_energy = 0, worst_angle = 0;
    const double e0 = energy_of(model, start);
    for (std::size_t i = 0; i < r.t.size(); ++i) {
      worst_centre = std::max(worst_centre, (r.s[i].position_world - start.position_world).norm());
      worst_energy = std::max(worst_energy, std::abs(energy_of(model, r.s[i]) - e0) / e0);
      // The axis precesses about e_z at Omega: its azimuth is Omega t.
      const Vector3d bt = r.s[i].orientation * Vector3d::UnitZ();
      const double azimuth = std::atan2(bt.y(), bt.x());
      const double expected = std::remainder(rate * r.t[i], 2 * M_PI);
      worst_angle = std::max(worst_angle, std::abs(std::remainder(azimuth - expected, 2 * M_PI)));
      EXPECT_NEAR(std::acos(bt.z()), alpha, 1e-10);
    }
    EXPECT_LT(worst_centre, 1e-13);
    EXPECT_LT(worst_energy, 1e-12);
    EXPECT_LT(worst_angle, 1e-11);
    expect_energy_never_rises(r);
    EXPECT_LT(r.worst_gap, 1e-17);
    const std::string name = "rim rolling at " + std::to_string(int(alpha_deg)) + " deg";
    report(name + ": centre drift (m)", worst_centre);
    report(name + ": energy drift (relative)", worst_energy);
    report(name + ": precession phase error (rad)", worst_angle);
    if (alpha_deg == 75) report_cost("rim rolling (75 deg)", phase.counters(), t_end);
  }
}

// ---------------------------------------------------------------------------------------------
// Conservation: Jellett's integral

TEST(PlaneContact, JellettsIntegralIsConservedThroughSlidingAndRolling) {
  // J = L . (x_G - P) is conserved for any force at P (its torque is normal to r) on a cap:
  // a tilted, spinning, sliding stone that then sticks and rolls (no couples).
  const auto model = stone_model();
  const Quaterniond q =
      Quaterniond(Eigen::AngleAxisd(0.4, Vector3d::UnitZ())) * tilt_about_y(12 * kDeg);
  const Vector3d b = q * Vector3d::UnitZ();
  const Vector3d omega = 40.0 * b + Vector3d(3.0, -2.0, 0.0);
  vg::PlaneContact phase(model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(),
                         material(0.3, 0, 0),
                         on_plane(model, q, Vector2d::Zero(), Vector2d(0.4, 0.1), omega), 0.0);
  auto jellett = [&](const vg::RigidBodyState& s) {
    return s.angular_momentum_world.dot(-lowest_offset(s.orientation));
  };
  const double j0 = jellett(phase.state_at(0.0));
  const Trace r = trace(phase, model, 1.0, 1e-3);
  double worst = 0;
  bool stuck_seen = false;
  for (std::size_t i = 0; i < r.t.size(); ++i)
    worst = std::max(worst, std::abs(jellett(r.s[i]) - j0));
  for (const auto& e : r.events) {
    stuck_seen |= e.event == vg::PlaneContactEvent::slip_stop;
    EXPECT_NE(e.mode.part, vg::LensPart::rim);
  }
  EXPECT_TRUE(stuck_seen);
  EXPECT_LT(worst / std::abs(j0), 1e-11);
  EXPECT_LT(r.worst_gap, 1e-17);
  expect_energy_never_rises(r);
  report("Jellett: worst |J - J0| / |J0|", worst / std::abs(j0));
  for (const auto& e : r.events) {
    std::cout << "[ event    ] " << e.time_s << " " << vg::plane_contact_event_name(e.event)
              << "\n";
  }
  report_cost("sliding+spinning tilted (Jellett case)", phase.counters(), 1.0);
}

// ---------------------------------------------------------------------------------------------
// The cap/rim switch, lift-off, slip and stick

namespace {

// Frictionless planar rocking at any tilt: G stays above its start, z_G = rho(cos(theta)).
bool on_cap(double theta) { return std::cos(theta) >= kD / kR; }
double reach_at(double theta) {
  return on_cap(theta) ? kR - kD * std::cos(theta) : kA * std::sin(std::abs(theta));
}
double frictionless_inertia(double theta) {
  // z_G' = (d sin(theta)) theta' on the cap, (a cos(theta)) theta' on the rim.
  const double lever = on_cap(theta) ? kD * std::sin(theta) : kA * std::cos(theta);
  return kI1 + kM * lever * lever;
}
// m g (rho(theta0) - rho(theta)) for theta0 on the rim; on the rim a (sin theta0 - sin theta)
// written without cancellation near the turning point.
double frictionless_drop(double theta0, double theta, double difference) {
  if (on_cap(theta)) return kM * kG * (reach_at(theta0) - reach_at(theta));
  return kM * kG * 2 * kA * std::cos(0.5 * (theta0 + theta)) * std::sin(0.5 * difference);
}

}  // namespace

TEST(PlaneContact, FrictionlessRockingAcrossTheCapRimSwitch) {
  // Released at 60 deg (on the rim, beyond beta = 45.39 deg): rim -> cap -> rim -> ... with no
  // impulse and no energy change; event times and the period from the energy integral.
  const double theta0 = 60 * kDeg, beta = std::acos(kD / kR);
  EXPECT_NEAR(beta / kDeg, 45.388, 1e-3);
  const auto model = stone_model();
  const auto start =
      on_plane(model, tilt_about_y(theta0), Vector2d::Zero(), Vector2d::Zero(), Vector3d::Zero());
  vg::PlaneContact phase(model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(),
                         material(0, 0, 0), start, 0.0);
  EXPECT_EQ(phase.mode().part, vg::LensPart::rim);
  const double quarter =
      ref::time_from_turning_point(frictionless_inertia, frictionless_drop, theta0, 0.0, {beta});
  const double to_switch =
      ref::time_from_turning_point(frictionless_inertia, frictionless_drop, theta0, beta);
  // Switch times within two periods: t = k T/2 +/- to_switch.
  std::vector<double> expected;
  for (int k = 0; k < 4; ++k) {
    expected.push_back(2 * k * quarter + to_switch);
    expected.push_back(2 * k * quarter + 4 * quarter / 2 - to_switch);
  }
  std::sort(expected.begin(), expected.end());
  Trace r;
  const auto zeros = crossings(
      phase, model, 8 * quarter - 1e-3, 1e-3,
      [](const vg::RigidBodyState& s) { return tilt_of(s); }, &r);
  ASSERT_EQ(r.events.size(), expected.size());
  double worst_time = 0;
  for (std::size_t i = 0; i < r.events.size(); ++i) {
    EXPECT_EQ(r.events[i].event,
              i % 2 == 0 ? vg::PlaneContactEvent::rim_to_cap : vg::PlaneContactEvent::cap_to_rim);
    worst_time = std::max(worst_time, std::abs(r.events[i].time_s - expected[i]));
    EXPECT_NEAR(std::abs(tilt_of(r.events[i].state)), beta, 1e-12);
  }
  EXPECT_LT(worst_time, 1e-11);
  const double period = measured_period(zeros);
  EXPECT_NEAR(period, 4 * quarter, 1e-11);
  const double e0 = energy_of(model, start);
  double worst_energy = 0;
  for (const auto& s : r.s) {
    worst_energy = std::max(worst_energy, std::abs(energy_of(model, s) - e0) / e0);
    EXPECT_NEAR(s.position_world.x(), 0.0, 1e-15);
  }
  EXPECT_LT(worst_energy, 1e-10);  // the energy guard's one-sided clipping: a slow loss
  EXPECT_LT(r.worst_gap, 1e-17);
  expect_energy_never_rises(r);
  report("cap/rim rocking from 60 deg: worst switch time error (s)", worst_time);
  report("cap/rim rocking from 60 deg: period (s)", period);
  report("cap/rim rocking from 60 deg: period - energy integral (s)", period - 4 * quarter);
  report("cap/rim rocking from 60 deg: energy drift (relative)", worst_energy);
}

TEST(PlaneContact, LiftOffFromTheRimWhereTheNormalForceVanishes) {
  // Frictionless, on the rim at 50 deg tipping up at 33 rad/s: G only moves vertically,
  // z = a sin(alpha), E = 1/2 (I1 + m a^2 cos^2 alpha) alpha'^2 + m g a sin(alpha), and
  // N = m (g - a sin(alpha) alpha'^2) / (1 + m a^2 cos^2(alpha) / I1) reaches 0 when
  // a sin(alpha) alpha'^2 = g.
  const double alpha0 = 50 * kDeg, rate0 = 33.0;
  const double energy = 0.5 * (kI1 + kM * kA * kA * std::pow(std::cos(alpha0), 2)) * rate0 * rate0 +
                        kM * kG * kA * std::sin(alpha0);
  auto rate_sq = [&](double alpha) {
    return 2 * (energy - kM * kG * kA * std::sin(alpha)) /
           (kI1 + kM * kA * kA * std::pow(std::cos(alpha), 2));
  };
  auto margin = [&](double alpha) { return kG - kA * std::sin(alpha) * rate_sq(alpha); };
  ASSERT_GT(margin(alpha0), 0);
  double lo = alpha0, hi = 80 * kDeg;
  ASSERT_LT(margin(hi), 0);
  for (int i = 0; i < 200; ++i) (margin(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
  const double alpha_lift = 0.5 * (lo + hi);
  const double t_lift = boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
      [&](double a) { return 1 / std::sqrt(rate_sq(a)); }, alpha0, alpha_lift, 15, 1e-15);

  const auto model = stone_model();
  vg::PlaneContact phase(model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(),
                         material(0, 0, 0),
                         on_plane(model, tilt_about_y(alpha0), Vector2d::Zero(), Vector2d::Zero(),
                                  Vector3d(0, rate0, 0)),
                         0.0);
  const Trace r = trace(phase, model, 1.0, 1e-3);
  ASSERT_EQ(r.events.size(), 1u);
  const auto& lift = r.events.front();
  EXPECT_EQ(lift.event, vg::PlaneContactEvent::lift_off);
  EXPECT_TRUE(lift.finished);
  EXPECT_NEAR(lift.time_s, t_lift, 1e-12);
  EXPECT_NEAR(tilt_of(lift.state), alpha_lift, 1e-11);
  EXPECT_NEAR(omega_of(model, lift.state).y(), std::sqrt(rate_sq(alpha_lift)), 1e-8);
  EXPECT_NEAR(phase.forces_at(lift.time_s).normal_force_n, 0.0, 1e-12 * kM * kG);
  EXPECT_NEAR(gap_of(lift.state, 0.0), 0.0, 1e-17);
  // The phase is over: the same time may be asked again, no later one.
  EXPECT_EQ(phase.advance(lift.time_s).event, vg::PlaneContactEvent::lift_off);
  EXPECT_THROW(phase.advance(lift.time_s + 1e-3), vg::InvalidArgument);
  expect_energy_never_rises(r);
  report("lift-off: time - quadrature (s)", lift.time_s - t_lift);
  report("lift-off: tilt - closed form (rad)", tilt_of(lift.state) - alpha_lift);
}

TEST(PlaneContact, LowFrictionRockingSlipsAndSticksAsThePlanarModelSays) {
  // Released at 25 deg with mu 0.1: the friction a rolling rock needs exceeds mu N, so the
  // contact point slips, sticks again, slips... Every mode change against the planar model.
  const double mu = 0.1, theta0 = 25 * kDeg;
  const auto model = stone_model();
  vg::PlaneContact phase(
      model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(), material(mu, 0, 0),
      on_plane(model, tilt_about_y(theta0), Vector2d::Zero(), Vector2d::Zero(), Vector3d::Zero()),
      0.0);
  const ref::PlanarCap planar(kM, kI1, kR, kD, kG, mu, 0.0);
  ref::PlanarCap::Mode mode;
  mode.tangential = ref::PlanarCap::Tangential::stick;
  mode = planar.choose({0, theta0, 0, 0}, mode, true, false);
  const auto all_ref_events =
      planar.run({0, theta0, 0, 0}, mode, 0.4, 1e-6, [](double, const auto&) {});
  // Slip reversing through zero is no mode change (the module handles it inside).
  std::vector<ref::PlanarCap::Event> ref_events;
  for (const auto& e : all_ref_events) {
    if (e.mode_before.tangential != e.mode_after.tangential) ref_events.push_back(e);
  }
  const Trace r = trace(phase, model, 0.4, 1e-3);
  ASSERT_GE(ref_events.size(), 3u);
  ASSERT_EQ(r.events.size(), ref_events.size());
  double worst_time = 0, worst_x = 0;
  for (std::size_t i = 0; i < r.events.size(); ++i) {
    const bool sticks = ref_events[i].mode_after.tangential == ref::PlanarCap::Tangential::stick;
    EXPECT_EQ(r.events[i].event,
              sticks ? vg::PlaneContactEvent::slip_stop : vg::PlaneContactEvent::slip_start);
    worst_time = std::max(worst_time, std::abs(r.events[i].time_s - ref_events[i].time));
    worst_x =
        std::max(worst_x, std::abs(r.events[i].state.position_world.x() - ref_events[i].state.x));
  }
  EXPECT_LT(worst_time, 1e-10);
  EXPECT_LT(worst_x, 1e-12);
  EXPECT_LT(r.worst_gap, 1e-17);
  expect_energy_never_rises(r);
  report("stick/slip rocking: mode changes in 0.4 s", static_cast<double>(r.events.size()));
  report("stick/slip rocking: worst event time - planar reference (s)", worst_time);
  report("stick/slip rocking: worst x_G at events - planar reference (m)", worst_x);
}

// ---------------------------------------------------------------------------------------------
// Regions, other planes, bad input

TEST(PlaneContact, AnObstacleIsMetWhereASearchOfTheFreeTrajectoryFindsItWithFewClearanceLookUps) {
  // A wall x = x_w is the obstacle: clearance x_w - x_G - reach(b_x), the exact distance of the
  // lens to the half-space. The clearance is evaluated only where the motion since its last value
  // could have used that value up, so the phase with the wall must follow the free phase bit for
  // bit and end where the free trajectory first reaches the wall (found here by bisection on its
  // states), while looking the clearance up less than once every two steps where the wall is not
  // right beside the stone. Three motions: the
  // slide of 0.5 m/s (mu 0.3, rolling resistance 2 um), which slips 42 mm and then rocks with
  // the contact stuck; frictionless rocking from 5 deg, where G stays on its vertical; and
  // rolling on the rim in place at 60 deg, where G stays still and only the turning of the lens
  // brings it to the wall.
  const auto model = stone_model();
  const double rim_rate = std::sqrt(kM * kG * kA / (kI1 * std::sin(60 * kDeg)));
  const Vector3d rim_axis = tilt_about_y(60 * kDeg) * Vector3d::UnitZ();
  const double t_end = 1.0, dt = 1e-3;
  auto front = [](const vg::RigidBodyState& s) {
    return s.position_world.x() + kLens.reach((s.orientation * Vector3d::UnitZ()).x());
  };
  struct Case {
    vg::RigidBodyState start;
    vg::ContactMaterial law;
    // The wall `depth` inside the front's farthest reach after `after_s`: deep enough that the
    // front stays beyond it longer than the longest step (5 ms), as events are sign changes
    // between step ends.
    double after_s, depth;
    double wall_early, wall_never;
  };
  const Case cases[] = {
      {on_plane(model, Quaterniond::Identity(), Vector2d::Zero(), Vector2d(0.5, 0),
                Vector3d::Zero()),
       material(0.3, 2e-6, 0.0), 0.3, 5e-6, 0.03, 0.2},
      {on_plane(model, tilt_about_y(5 * kDeg), Vector2d::Zero(), Vector2d::Zero(),
                Vector3d::Zero()),
       material(0.0, 0.0, 0.0), 0.1, 5e-6, -1.0, 0.2},
      {on_plane(model, tilt_about_y(60 * kDeg), Vector2d::Zero(), Vector2d::Zero(),
                rim_rate * (Vector3d::UnitZ() - std::cos(60 * kDeg) * rim_axis)),
       material(0.9, 0.0, 0.0), 0.01, 5e-4, -1.0, 0.2},
  };
  for (const Case& c : cases) {
    vg::PlaneContact free_phase(model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(), c.law,
                                c.start, 0.0);
    const Trace free_trace = trace(free_phase, model, t_end, dt);
    double farthest = -1.0;
    for (std::size_t i = 0; i < free_trace.t.size(); ++i) {
      if (free_trace.t[i] > c.after_s) farthest = std::max(farthest, front(free_trace.s[i]));
    }
    for (const double wall : {c.wall_early, farthest - c.depth, c.wall_never}) {
      if (wall < 0.0) continue;
      auto gap = [wall, &front](const vg::RigidBodyState& s) { return wall - front(s); };
      vg::PlaneContact reference(model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(), c.law,
                                 c.start, 0.0);
      const auto hits = crossings(reference, model, t_end, dt, gap);
      long look_ups = 0;
      vg::PlaneContactOptions options;
      options.clearance_m = [wall, &look_ups](const vg::LensPose& pose) {
        ++look_ups;
        return wall - pose.center_world.x() - kLens.reach(pose.axis_world.x());
      };
      vg::PlaneContact phase(model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(), c.law,
                             c.start, 0.0, options);
      // Look-ups and steps up to the last grid time before the end (the search at the wall
      // aside).
      long look_ups_before = 0, steps_before = 0, look_ups_at_grid = 0, steps_at_grid = 0;
      const Trace r = trace(phase, model, t_end, dt, 0.0, [&](double, double) {
        look_ups_before = look_ups_at_grid;
        steps_before = steps_at_grid;
        look_ups_at_grid = look_ups;
        steps_at_grid = phase.counters().steps;
      });
      if (hits.empty()) {
        EXPECT_NE(r.last.event, vg::PlaneContactEvent::obstacle) << wall;
      } else {
        ASSERT_EQ(r.last.event, vg::PlaneContactEvent::obstacle) << wall;
        EXPECT_NEAR(r.last.time_s, hits.front().t, 1e-12) << wall;
        EXPECT_NEAR(gap(r.last.state), 0.0, 1e-15) << wall;
      }
      // Up to the wall, the same trajectory as without it.
      for (std::size_t i = 0; i + 1 < r.t.size(); ++i) {
        ASSERT_EQ(r.t[i], free_trace.t[i]);
        EXPECT_EQ(r.s[i].position_world, free_trace.s[i].position_world) << wall << " " << r.t[i];
        EXPECT_EQ(r.s[i].angular_momentum_world, free_trace.s[i].angular_momentum_world);
      }
      // Once a step without the bound; a wall within micrometres of a rocking stone is looked up
      // about that often.
      if (wall == c.wall_early || wall == c.wall_never) {
        EXPECT_LT(2 * look_ups_before, steps_before) << wall;
      }
      report("wall at " + std::to_string(wall) + " m: clearance look-ups per step",
             static_cast<double>(look_ups_before) / static_cast<double>(steps_before));
    }
  }
}

TEST(PlaneContact, LeavingTheBoardTopAndEnteringTheBoardsFootprintOnTheTable) {
  // Rotation frozen, flat: the contact point is under G, x(t) = x0 + v0 t - mu g t^2 / 2.
  const vg::BoardGeometry board;
  const double mu = 0.3, v0 = 0.5;
  const auto model = frozen_rotation_model();
  const double hx = board.half_extent_m().x();
  struct Case {
    double h0, x0;
    vg::PlaneRegion region;
  };
  const Case cases[] = {
      {board.top_z_m(), 0.19, vg::PlaneRegion::inside(Vector2d::Zero(), board.half_extent_m())},
      {board.table_z_m(), -0.25,
       vg::PlaneRegion::outside(Vector2d::Zero(), board.half_extent_m())}};
  for (const Case& c : cases) {
    const double distance = c.x0 < 0 ? -hx - c.x0 : hx - c.x0;
    const double t_cross = (v0 - std::sqrt(v0 * v0 - 2 * mu * kG * distance)) / (mu * kG);
    vg::PlaneContact phase(model, kLens, kGravity, c.h0, c.region, material(mu, 0, 0),
                           on_plane(model, Quaterniond::Identity(), Vector2d(c.x0, 0.05),
                                    Vector2d(v0, 0), Vector3d::Zero(), c.h0),
                           0.0);
    const Trace r = trace(phase, model, 1.0, 1e-2, c.h0);
    ASSERT_EQ(r.events.size(), 1u);
    EXPECT_EQ(r.last.event, vg::PlaneContactEvent::left_region);
    EXPECT_NEAR(r.last.time_s, t_cross, 1e-13);
    EXPECT_NEAR(r.last.state.position_world.x(), c.x0 < 0 ? -hx : hx, 1e-14);
    EXPECT_NEAR(r.last.state.position_world.z(), c.h0 + kC, 1e-15);
    EXPECT_LT(r.worst_gap, 1e-16);
    expect_energy_never_rises(r);
  }
}

TEST(PlaneContact, AnObstacleWithinOneLongStepIsFoundByTheLooksOnItsDenseOutput) {
  // Rotation frozen, flat, sliding along x past a post of radius r whose axis is dy beside the
  // path: the clearance |G - post| - r (horizontal) is negative only while
  // |x - post_x| < sqrt(r^2 - dy^2), about 15 ms here, inside one integrator step of the smooth
  // slide. Hit at x(t) = post_x - sqrt(r^2 - dy^2), x(t) = x0 + v0 t - mu g t^2 / 2.
  const double mu = 0.3, v0 = 0.5, r = 3e-3, dy = 1e-3;
  const auto model = frozen_rotation_model();
  const Vector2d x0(0.01, 0.02), post(x0.x() + 0.02, x0.y() + dy);
  const double distance = post.x() - std::sqrt(r * r - dy * dy) - x0.x();
  const double t_hit = (v0 - std::sqrt(v0 * v0 - 2 * mu * kG * distance)) / (mu * kG);
  for (const double resolution : {vg::PlaneContactOptions().event_resolution_s, 1.0}) {
    vg::PlaneContactOptions options;
    options.event_resolution_s = resolution;
    options.clearance_m = [post, r](const vg::LensPose& pose) {
      return (pose.center_world.head<2>() - post).norm() - r;
    };
    vg::PlaneContact phase(
        model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(), material(mu, 0, 0),
        on_plane(model, Quaterniond::Identity(), x0, Vector2d(v0, 0), Vector3d::Zero()), 0.0,
        options);
    const Trace r_trace = trace(phase, model, 1.0, 0.1);
    if (resolution < 1.0) {
      ASSERT_EQ(r_trace.last.event, vg::PlaneContactEvent::obstacle);
      EXPECT_NEAR(r_trace.last.time_s, t_hit, 1e-12);
      // Fewer steps than looks: the hit lay inside a step (which a step end alone misses, below).
      EXPECT_LT(phase.counters().steps, static_cast<long>(t_hit / resolution));
    } else {
      // Looked at only at the step ends, the slide passes the post and rests beyond it.
      EXPECT_EQ(r_trace.last.event, vg::PlaneContactEvent::rest);
      EXPECT_GT(r_trace.last.state.position_world.x(), post.x() + r);
    }
    expect_energy_never_rises(r_trace);
  }
}

TEST(PlaneContact, UpsideDownOnTheTableRocksLikeTheRightWayUp) {
  // The top cap on the table plane: the same rolling period at 5 deg as on the bottom cap.
  const auto model = stone_model();
  const double theta0 = 5 * kDeg, h0 = -0.1515;
  const Quaterniond upside_down =
      tilt_about_y(theta0) * Quaterniond(Eigen::AngleAxisd(M_PI, Vector3d::UnitX()));
  vg::PlaneContact phase(
      model, kLens, kGravity, h0, vg::PlaneRegion::whole_plane(), material(0.3, 0, 0),
      on_plane(model, upside_down, Vector2d(0.3, 0.3), Vector2d::Zero(), Vector3d::Zero(), h0),
      0.0);
  EXPECT_EQ(phase.mode().part, vg::LensPart::top_cap);
  Trace r;
  const auto zeros = crossings(
      phase, model, 0.7, 1e-3,
      [](const vg::RigidBodyState& s) {
        const Vector3d b = s.orientation * Vector3d::UnitZ();
        return b.x();
      },
      &r, h0);
  const double exact = ref::oscillation_period(rolling_inertia, cap_drop, theta0);
  EXPECT_NEAR(measured_period(zeros), exact, 1e-10);
  EXPECT_LT(r.worst_gap, 1e-16);
  expect_energy_never_rises(r);
}

TEST(PlaneContact, BadInputIsRefusedByNameAndChangesNothing) {
  const auto model = stone_model();
  const auto flat = on_plane(model, Quaterniond::Identity(), Vector2d::Zero(), Vector2d::Zero(),
                             Vector3d::Zero());
  auto message = [&](vg::RigidBodyState s, vg::ContactMaterial m, vg::PlaneRegion region) {
    try {
      vg::PlaneContact phase(model, kLens, kGravity, 0.0, region, m, s, 0.0);
    } catch (const vg::InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const auto whole = vg::PlaneRegion::whole_plane();
  auto above = flat;
  above.position_world.z() += 1e-6;
  EXPECT_NE(message(above, material(0.3, 0, 0), whole).find("gap"), std::string::npos);
  auto separating = flat;
  separating.velocity_world.z() = 0.01;
  EXPECT_NE(message(separating, material(0.3, 0, 0), whole).find("normal velocity"),
            std::string::npos);
  EXPECT_NE(message(flat, material(-1, 0, 0), whole).find("friction"), std::string::npos);
  EXPECT_NE(message(flat, material(0.3, NAN, 0), whole).find("rolling_resistance"),
            std::string::npos);
  const auto elsewhere = vg::PlaneRegion::inside(Vector2d(1, 1), Vector2d(0.1, 0.1));
  EXPECT_NE(message(flat, material(0.3, 0, 0), elsewhere).find("outside"), std::string::npos);
  auto nan_state = flat;
  nan_state.velocity_world.x() = NAN;
  EXPECT_NE(message(nan_state, material(0.3, 0, 0), whole).find("velocity"), std::string::npos);
  for (const double resolution_s : {0.0, -1e-3, static_cast<double>(NAN)}) {
    vg::PlaneContactOptions options;
    options.event_resolution_s = resolution_s;
    try {
      vg::PlaneContact phase(model, kLens, kGravity, 0.0, whole, material(0.3, 0, 0), flat, 0.0,
                             options);
      ADD_FAILURE() << "event_resolution_s " << resolution_s << " accepted";
    } catch (const vg::InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find("event_resolution_s"), std::string::npos) << e.what();
    }
  }

  vg::PlaneContact phase(
      model, kLens, kGravity, 0.0, whole, material(0.3, 0, 0),
      on_plane(model, tilt_about_y(0.1), Vector2d::Zero(), Vector2d::Zero(), Vector3d::Zero()),
      0.0);
  phase.advance(0.05);
  const vg::RigidBodyState at = phase.state_at(0.05);
  EXPECT_THROW(phase.advance(NAN), vg::InvalidArgument);
  EXPECT_THROW(phase.advance(0.01), vg::InvalidArgument);
  EXPECT_THROW(phase.state_at(0.06), vg::InvalidArgument);
  EXPECT_THROW(phase.state_at(INFINITY), vg::InvalidArgument);
  EXPECT_EQ(phase.time_reached(), 0.05);
  EXPECT_TRUE(phase.state_at(0.05) == at);
}

TEST(PlaneContact, AReleasedSlipFollowsCoulombsDirectionFromItsStart) {
  // A spinning, wobbling stone upside down on the plane (a state a toss reached) sticks, then
  // its friction reaches mu N and it slips again. Released continuously, the slip starts from
  // zero with zero acceleration; its direction is set by the dynamics, and near zero slip it is
  // a fast variable slaved to the consistent direction (the slip acceleration along the slip).
  // Coulomb's law must hold through the direction layer: the friction opposes the slip, inside
  // the layer (where the law uses that consistent direction) within a small angle, outside it
  // exactly. A fixed direction inside the layer left it 40 degrees off, and the jump at the
  // layer's edge cost 10^4 integrator steps within 10 us.
  const auto model = stone_model();
  const Quaterniond q(-0.22125920287387663, -0.45038169161826735, 0.85825401178367688,
                      -0.10770676977752625);
  const Vector3d omega(-27.48360398230782, -3.7575572015882059, 16.603267101843407);
  vg::PlaneContact phase(model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(),
                         material(0.3, 5e-6, 15e-6),
                         on_plane(model, q.normalized(), Vector2d(0.056, 0.068),
                                  Vector2d(0.049159130811130783, 0.11493913525239269), omega),
                         0.0);
  // To the first release of the contact point.
  vg::PlaneContactOutcome o;
  double t = 0.0;
  do {
    t += 1e-3;
    o = phase.advance(t);
    if (o.event != vg::PlaneContactEvent::none) t = o.time_s;
    ASSERT_LT(t, 1.0);
  } while (o.event != vg::PlaneContactEvent::slip_start);
  const long steps_at_release = phase.counters().steps;
  const double layer = vg::kSlipDirectionLayer;
  double worst_inside = 0.0, worst_outside = 0.0;
  int inside = 0, outside = 0;
  for (int i = 1; i <= 20000 && outside < 50; ++i) {
    const double ts = o.time_s + i * 1e-6;
    const vg::PlaneContactOutcome s = phase.advance(ts);
    ASSERT_EQ(s.event, vg::PlaneContactEvent::none);
    const Vector3d w = omega_of(model, s.state);
    Vector3d u = s.state.velocity_world + w.cross(lowest_offset(s.state.orientation));
    u.z() = 0.0;
    const Vector3d f = phase.forces_at(ts).friction_force_world;
    if (u.norm() < 0.3 * layer) continue;
    const double angle = std::acos(std::clamp(-f.normalized().dot(u.normalized()), -1.0, 1.0));
    if (u.norm() < layer) {
      worst_inside = std::max(worst_inside, angle);
      ++inside;
    } else {
      worst_outside = std::max(worst_outside, angle);
      ++outside;
    }
  }
  EXPECT_GT(inside, 10);
  EXPECT_EQ(outside, 50);
  EXPECT_LE(worst_inside, 0.02);
  EXPECT_LE(worst_outside, 1e-6);
  report("released slip: worst angle of -F_t to the slip inside the layer (rad)", worst_inside);
  report("released slip: worst angle outside it (rad)", worst_outside);
  report("released slip: integrator steps until it left the layer",
         static_cast<double>(phase.counters().steps - steps_at_release));
}

// The direction a part released from zero motion takes, found by brute force: its force at the
// bound against s, the other parts as in `mode`; the zeros of (s x a)_z on a fine scan of the
// circle, refined by bisection, with s . a > 0, the one nearest the hint.
Vector3d released_direction_by_scan(const vg::PlaneContactSetup& setup, vg::PlaneContactMode mode,
                                    const vg::PlaneContactKinematics& k, bool tangential,
                                    const Vector3d& hint) {
  auto residual = [&](double angle, double* along) {
    vg::ContactLawPart& part = tangential ? mode.tangential : mode.rolling;
    part.law = vg::ContactLaw::sliding;
    part.reference_world = Vector3d(std::cos(angle), std::sin(angle), 0.0);
    const vg::PlaneContactForces f = vg::solve_plane_contact(setup, mode, k);
    Vector3d acc = tangential ? f.slip_acceleration_world : f.angular_acceleration_world;
    acc.z() = 0.0;
    if (along) *along = part.reference_world.dot(acc);
    return part.reference_world.cross(acc).z();
  };
  const int n = 4096;
  Vector3d best = hint;
  double best_alignment = -2.0;
  double previous = residual(0.0, nullptr);
  for (int i = 1; i <= n; ++i) {
    double lo = 2 * M_PI * (i - 1) / n, hi = 2 * M_PI * i / n;
    const double value = residual(hi, nullptr);
    if ((previous <= 0.0) != (value <= 0.0)) {
      double f_lo = previous;
      for (int j = 0; j < 100 && hi - lo > 1e-14; ++j) {
        const double mid = 0.5 * (lo + hi);
        const double fm = residual(mid, nullptr);
        if ((fm <= 0.0) == (f_lo <= 0.0)) {
          lo = mid;
          f_lo = fm;
        } else {
          hi = mid;
        }
      }
      double along = 0.0;
      const double root = 0.5 * (lo + hi);
      residual(root, &along);
      const Vector3d s(std::cos(root), std::sin(root), 0.0);
      if (along > 0.0 && s.dot(hint) > best_alignment) {
        best_alignment = s.dot(hint);
        best = s;
      }
    }
    previous = value;
  }
  return best;
}

TEST(PlaneContact, AReleasedPartTakesTheConsistentDirectionABruteForceScanFinds) {
  // Stones set down tilted, with their contact point and rolling still and some spin: held
  // stuck they would need more friction or rolling couple than the law gives, so the mode
  // choice releases the part that exceeds its bound most, in the consistent direction (the
  // part's acceleration along it) nearest the reverse of the force it needed. That direction
  // against a brute-force scan of 4096 directions with a force solve each.
  const auto model = stone_model();
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int tangential_released = 0, rolling_released = 0;
  double worst = 0.0;
  long most_solves = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const double tilt = (3.0 + 84.0 * unit(rng)) * kDeg;
    const double heading = 2 * M_PI * unit(rng);
    const Quaterniond q = Quaterniond(Eigen::AngleAxisd(heading, Vector3d::UnitZ())) *
                          tilt_about_y(tilt) *
                          Quaterniond(Eigen::AngleAxisd(2 * M_PI * unit(rng), Vector3d::UnitZ()));
    const double spin = 40.0 * (unit(rng) - 0.5);
    const Vector3d omega(0, 0, spin);
    const Vector3d v = -omega.cross(lowest_offset(q));  // contact point still
    // Odd trials: a rolling resistance that holds most tilts, low friction (the slip released).
    const vg::ContactMaterial law =
        trial % 2 ? material(0.05, 0.02, 15e-6) : material(0.3, 5e-6, 15e-6);
    const vg::RigidBodyState start = on_plane(model, q, Vector2d(0.01, -0.02), v.head<2>(), omega);
    vg::PlaneContact phase(model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(), law, start,
                           0.0);
    const vg::PlaneContactMode chosen = phase.mode();
    // The reference: every part with zero motion stuck, the worst one released.
    const vg::PlaneContactSetup& setup = phase.setup();
    vg::PlaneContactMode stuck;
    stuck.part = chosen.part;
    stuck.tangential.law = stuck.rolling.law = vg::ContactLaw::stuck;
    stuck.spinning.law =
        std::abs(spin) > vg::kZeroAngularSpeed ? vg::ContactLaw::sliding : vg::ContactLaw::stuck;
    stuck.spinning.reference_world = Vector3d(0, 0, spin > 0 ? 1.0 : -1.0);
    const vg::RigidBodyState s0 = phase.state_at(0.0);
    const vg::PlaneContactKinematics k =
        vg::plane_contact_kinematics(setup, stuck, s0.position_world.head<2>(), s0.orientation,
                                     s0.velocity_world.head<2>(), omega_of(model, s0));
    const vg::PlaneContactForces f = vg::solve_plane_contact(setup, stuck, k);
    ASSERT_TRUE(f.solved);
    if (f.normal_force_n <= 0.0) continue;  // lifts off at once
    const double ratio_t = f.friction_force_world.norm() / (law.friction * f.normal_force_n);
    const double ratio_r =
        f.rolling_couple_world.norm() / (law.rolling_resistance_m * f.normal_force_n);
    if (std::max(ratio_t, ratio_r) <= 1.0) continue;  // holds: nothing released
    const bool tangential = ratio_t > ratio_r;
    const Vector3d needed = tangential ? f.friction_force_world : f.rolling_couple_world;
    const Vector3d expected =
        released_direction_by_scan(setup, stuck, k, tangential, -needed.normalized());
    const vg::ContactLawPart& part = tangential ? chosen.tangential : chosen.rolling;
    ASSERT_EQ(part.law, vg::ContactLaw::sliding) << "trial " << trial;
    const Vector3d got = part.reference_world.normalized();
    const double angle = std::atan2(got.cross(expected).norm(), got.dot(expected));
    EXPECT_LT(angle, 1e-9) << "trial " << trial << (tangential ? " tangential" : " rolling");
    worst = std::max(worst, angle);
    ++(tangential ? tangential_released : rolling_released);
    // The direction is found from a fit of the residual (a handful of force solves), not by a
    // scan of the circle with a solve per direction (64 and more).
    EXPECT_LE(phase.counters().extra_solves, 40) << "trial " << trial;
    most_solves = std::max(most_solves, phase.counters().extra_solves);
  }
  EXPECT_GE(tangential_released, 5);
  EXPECT_GE(rolling_released, 5);
  report("released direction: worst angle to the brute-force scan (rad)", worst);
  report("released direction: tangential releases checked", tangential_released);
  report("released direction: rolling releases checked", rolling_released);
  report("released direction: most force solves to choose a mode", most_solves);
}

TEST(PlaneContact, SlidingCost) {
  // Work per simulated second while sliding (the free slide until the slip stops).
  const auto model = stone_model();
  vg::PlaneContact phase(model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(),
                         material(0.3, 5e-6, 15e-6),
                         on_plane(model, Quaterniond::Identity(), Vector2d::Zero(),
                                  Vector2d(0.5, 0), Vector3d(0, 0, 20)),
                         0.0);
  const auto o = phase.advance(1.0);
  EXPECT_NE(o.event, vg::PlaneContactEvent::none);
  report_cost("sliding (0.5 m/s, spinning 20 rad/s, until " +
                  std::string(vg::plane_contact_event_name(o.event)) + ")",
              phase.counters(), o.time_s);
}

TEST(PlaneContact, GeneralMotionSettlesToExactRestAndTheEnergyLostIsTheWorkOfTheLaws) {
  // Tilted, sliding, spinning and wobbling, default materials (mu 0.3, l_r 5 um, l_s 15 um).
  // Power balance: E(t0) - E(t) = int (mu N |u_t| + l_r N |omega_t| + l_s N |omega_z|) dt
  // (Simpson between samples, from the contact forces and the states), plus the tiny snaps.
  const auto model = stone_model();
  const vg::ContactMaterial law;  // the defaults
  const Quaterniond q =
      Quaterniond(Eigen::AngleAxisd(1.1, Vector3d::UnitZ())) * tilt_about_y(8 * kDeg);
  const Vector3d b = q * Vector3d::UnitZ();
  const auto start = on_plane(model, q, Vector2d(0.05, -0.02), Vector2d(0.3, 0.1),
                              25.0 * b + Vector3d(2.0, -3.0, 0.0));
  vg::PlaneContact phase(model, kLens, kGravity, 0.0, vg::PlaneRegion::whole_plane(), law, start,
                         0.0);
  auto power = [&](double t) {
    const vg::RigidBodyState s = phase.state_at(t);
    const vg::PlaneContactForces f = phase.forces_at(t);
    const Vector3d w = omega_of(model, s);
    const Vector3d u = s.velocity_world + w.cross(lowest_offset(s.orientation));
    // The law's power: friction and couples against the motion (zero when stuck).
    return -(f.friction_force_world.dot(u) + f.rolling_couple_world.dot(Vector3d(w.x(), w.y(), 0)) +
             f.spinning_couple_nm * w.z());
  };
  double dissipated = 0;
  const Trace r = trace(phase, model, 30.0, 1e-3, 0.0, [&](double t0, double t1) {
    if (!(t1 > t0)) return;
    const int n = 8;  // Simpson on n sub-intervals
    const double h = (t1 - t0) / n;
    double sum = power(t0) + power(t1);
    for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * power(t0 + i * h);
    dissipated += sum * h / 3;
  });
  ASSERT_EQ(r.last.event, vg::PlaneContactEvent::rest);
  const double e0 = energy_of(model, start), e_end = energy_of(model, r.last.state);
  EXPECT_NEAR(e0 - e_end, dissipated, 1e-6 * (e0 - e_end));
  // Exact rest on the static inequalities: m g d sin(tilt) <= l_r N with N = m g.
  EXPECT_EQ(r.last.state.velocity_world, Vector3d::Zero());
  EXPECT_EQ(r.last.state.angular_momentum_world, Vector3d::Zero());
  const Vector3d b_end = r.last.state.orientation * Vector3d::UnitZ();
  EXPECT_LE(std::sqrt(1 - b_end.z() * b_end.z()), law.rolling_resistance_m / kD + 1e-12);
  // Every reported event changed the mode; energy fell throughout.
  for (std::size_t i = 1; i < r.events.size(); ++i) {
    const auto& a = r.events[i - 1].mode;
    const auto& c = r.events[i].mode;
    EXPECT_TRUE(a.part != c.part || a.tangential.law != c.tangential.law ||
                a.rolling.law != c.rolling.law || a.spinning.law != c.spinning.law ||
                r.events[i].finished);
  }
  EXPECT_LT(r.worst_gap, 1e-17);
  expect_energy_never_rises(r);
  report("settling: time to rest (s)", r.last.time_s);
  report("settling: reported events", static_cast<double>(r.events.size()));
  report("settling: energy lost - dissipated work (relative)",
         (e0 - e_end - dissipated) / (e0 - e_end));
  for (const auto& e : r.events) {
    std::cout << "[ event    ] " << e.time_s << " " << vg::plane_contact_event_name(e.event)
              << "\n";
  }
  report_cost("settling (slide, spin, wobble to rest)", phase.counters(), r.last.time_s);
}
