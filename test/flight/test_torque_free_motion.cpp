// Torque-free rotation of the axisymmetric stone (rigid_body model): the closed form of
// docs/physics.md and ExactMotion against an independent RK4 integration of Euler's equations; a
// spin about the symmetry axis stays about it; an off-axis spin precesses at Omega = (I3 - I1)
// omega3 / I1 in the body and its axis sweeps a cone about L with cos(theta) = I3 omega3 / |L| at
// |L| / I1 - all measured from the integrated trajectories.
#include <gtest/gtest.h>

#include <cstdio>

#include "support/physics_reference.h"
#include "support/stone_setup.h"
#include "virtual_go/body/rigid_body.h"
#include "virtual_go/flight/exact_motion.h"
#include "virtual_go/flight/flight_cache.h"
#include "virtual_go/flight/integrator_registry.h"
#include "virtual_go/go/stone.h"

namespace vg = virtual_go;
using vgtest::Quat;
using vgtest::stone_setup;

namespace {

// A tilted stone spinning with body angular velocity omega_body.
vg::RigidBodyState spinning(const vg::MotionSetup& setup, const Eigen::Vector3d& omega_body) {
  vg::RigidBodyState s;
  s.orientation = vgtest::to_eigen(vgtest::axis_angle(Eigen::Vector3d(0.4, -0.9, 0.3)));
  const Eigen::Vector3d inertia = setup.model.mass_properties().principal_moments_body();
  s.angular_momentum_world =
      vgtest::rotate(vgtest::from_eigen(s.orientation), inertia.cwiseProduct(omega_body));
  return s;
}

// Unwrapped angle of the component of v orthogonal to axis, measured from the direction ref.
struct AngleTracker {
  Eigen::Vector3d axis, e1, e2;
  double last = 0.0, total = 0.0;
  AngleTracker(const Eigen::Vector3d& axis_in, const Eigen::Vector3d& ref) {
    axis = axis_in.normalized();
    e1 = (ref - ref.dot(axis) * axis).normalized();
    e2 = axis.cross(e1);
  }
  void update(const Eigen::Vector3d& v) {
    const double a = std::atan2(v.dot(e2), v.dot(e1));
    total += std::remainder(a - last, 2 * M_PI);
    last = a;
  }
};

}  // namespace

TEST(TorqueFreeMotion, ClosedFormAndExactMotionSolveEulersEquations) {
  const vg::MotionSetup setup = stone_setup();
  const Eigen::Vector3d inertia = setup.model.mass_properties().principal_moments_body();
  const Eigen::Vector3d omega_body0(12.0, -7.0, 30.0);
  const vg::RigidBodyState s0 = spinning(setup, omega_body0);
  const vgtest::AxisymmetricTop top{inertia.x(), inertia.z(), vgtest::from_eigen(s0.orientation),
                                    s0.angular_momentum_world};
  const vgtest::EulerEquationsReference euler{inertia};
  const vg::ExactMotion exact(setup, s0);
  vgtest::EulerEquationsReference::State ref{vgtest::from_eigen(s0.orientation), omega_body0};
  const double omega = top.body_precession_rate();
  double worst_closed = 0, worst_exact = 0;
  for (int k = 1; k <= 10; ++k) {  // t = 0.1 .. 1 s
    ref = euler.integrate(ref, 0.1, 5000);
    const double t = 0.1 * k;
    worst_closed = std::max(worst_closed, vgtest::angle_between(ref.q, top.orientation_at(t)));
    worst_exact =
        std::max(worst_exact,
                 vgtest::angle_between(ref.q, vgtest::from_eigen(exact.state_at(t).orientation)));
    // Body omega: omega3 constant, the transverse part turned by Rz(Omega t).
    const Eigen::Vector3d expected_body(
        std::cos(omega * t) * omega_body0.x() - std::sin(omega * t) * omega_body0.y(),
        std::sin(omega * t) * omega_body0.x() + std::cos(omega * t) * omega_body0.y(),
        omega_body0.z());
    EXPECT_LT((ref.omega_body - expected_body).norm(), 1e-9) << "t " << t;
  }
  std::printf("closed form vs RK4 of Euler's equations over 1 s: %.2e rad; ExactMotion: %.2e rad\n",
              worst_closed, worst_exact);
  EXPECT_LT(worst_closed, 1e-11);
  EXPECT_LT(worst_exact, 1e-11);
}

TEST(TorqueFreeMotion, SpinAboutTheSymmetryAxisStaysAboutIt) {
  const vg::MotionSetup setup = stone_setup();
  const double omega3 = 40.0;
  for (const std::string& name : vg::integrator_names()) {
    auto integrator = vg::make_integrator(name, setup);
    vg::FlightCache cache;  // the stone's own, carried from step to step
    vg::RigidBodyState s = spinning(setup, Eigen::Vector3d(0, 0, omega3));
    const Eigen::Vector3d axis0 = s.orientation * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d x0 = s.orientation * Eigen::Vector3d::UnitX();
    AngleTracker phase(axis0, x0);
    double worst_tilt = 0;
    const double dt = 1e-3;
    for (int i = 0; i < 2000; ++i) {
      integrator->advance(s, dt, cache);
      const Eigen::Vector3d axis = s.orientation * Eigen::Vector3d::UnitZ();
      worst_tilt = std::max(worst_tilt, std::atan2(axis.cross(axis0).norm(), axis.dot(axis0)));
      phase.update(s.orientation * Eigen::Vector3d::UnitX());
    }
    const double phase_lag = omega3 * 2.0 - phase.total;
    // With omega fixed along the axis each step is an exact turn about it by an angle that is
    // known in closed form: theta = omega3 dt for exact and splitting; for euler,
    // normalise(1 + dt omega / 2) turns by 2 atan(theta / 2); for rk4 the quaternion is scaled
    // by the degree-4 Taylor polynomial of exp(x J), x = theta / 2, J^2 = -1.
    const double theta = omega3 * dt, x = theta / 2;
    double step_angle = theta;
    if (name == "euler") step_angle = 2 * std::atan(x);
    if (name == "rk4") {
      step_angle = 2 * std::atan2(x - x * x * x / 6, 1 - x * x / 2 + x * x * x * x / 24);
    }
    const double predicted_lag = 2000 * (theta - step_angle);
    std::printf(
        "%-9s axial spin 2 s: axis tilt %.2e rad, spin phase lag %.6e rad (predicted %.6e)\n",
        name.c_str(), worst_tilt, phase_lag, predicted_lag);
    EXPECT_LT(worst_tilt, 1e-13) << name;
    EXPECT_NEAR(phase_lag, predicted_lag, 1e-11 + 1e-9 * std::abs(predicted_lag)) << name;
  }
}

TEST(TorqueFreeMotion, OffAxisSpinPrecessesAtTheTheoreticalRateOnTheTheoreticalCone) {
  const vg::MotionSetup setup = stone_setup();
  const Eigen::Vector3d inertia = setup.model.mass_properties().principal_moments_body();
  const double i1 = inertia.x(), i3 = inertia.z();
  const Eigen::Vector3d omega_body0(10.0, 0.0, 30.0);
  // Theory (docs/physics.md, "Flight in closed form").
  const double omega_body_rate = (i3 - i1) * omega_body0.z() / i1;
  const double l_norm = inertia.cwiseProduct(omega_body0).norm();
  const double cos_cone = i3 * omega_body0.z() / l_norm;
  const double cone_rate = l_norm / i1;
  std::printf("theory: Omega %.6f rad/s, cone angle %.6f rad, axis rate |L|/I1 %.6f rad/s\n",
              omega_body_rate, std::acos(cos_cone), cone_rate);

  // Tolerances follow each method's error at its dt and |omega| ~ 32 rad/s: exact to round-off,
  // splitting O((|omega| dt)^2), rk4 O((|omega| dt)^4), euler O(|omega| dt).
  struct Case {
    std::string name;
    double dt, rate_tol, cone_tol;
  };
  const double t_end = 1.0;
  for (const Case& c : {Case{"exact", 1e-3, 1e-12, 1e-14}, Case{"splitting", 1e-4, 1e-5, 1e-6},
                        Case{"rk4", 1e-3, 1e-7, 1e-8}, Case{"euler", 1e-5, 1e-3, 1e-3}}) {
    auto integrator = vg::make_integrator(c.name, setup);
    vg::FlightCache cache;  // the stone's own, carried from step to step
    vg::RigidBodyState s = spinning(setup, omega_body0);
    const Eigen::Vector3d l_hat = s.angular_momentum_world.normalized();
    vg::RigidBody body0(setup.model, s);
    AngleTracker body_phase(Eigen::Vector3d::UnitZ(), body0.angular_velocity_body());
    AngleTracker axis_phase(l_hat, s.orientation * Eigen::Vector3d::UnitZ());
    double worst_cone = 0, worst_omega3 = 0;
    const int n = static_cast<int>(std::lround(t_end / c.dt));
    for (int i = 0; i < n; ++i) {
      integrator->advance(s, c.dt, cache);
      const vg::RigidBody body(setup.model, s);
      const Eigen::Vector3d w_body = body.angular_velocity_body();
      const Eigen::Vector3d axis = s.orientation * Eigen::Vector3d::UnitZ();
      body_phase.update(w_body);
      axis_phase.update(axis);
      worst_cone = std::max(worst_cone, std::abs(axis.dot(l_hat) - cos_cone));
      worst_omega3 = std::max(worst_omega3, std::abs(w_body.z() - omega_body0.z()));
    }
    const double measured_body_rate = body_phase.total / t_end;
    const double measured_cone_rate = axis_phase.total / t_end;
    std::printf(
        "%-9s dt %g: Omega measured %.9f (rel err %.1e), axis rate %.9f (rel err %.1e), "
        "cone |cos - theory| max %.1e, omega3 drift max %.1e\n",
        c.name.c_str(), c.dt, measured_body_rate,
        std::abs(measured_body_rate / omega_body_rate - 1), measured_cone_rate,
        std::abs(measured_cone_rate / cone_rate - 1), worst_cone, worst_omega3);
    EXPECT_NEAR(measured_body_rate / omega_body_rate, 1.0, c.rate_tol) << c.name;
    EXPECT_NEAR(measured_cone_rate / cone_rate, 1.0, c.rate_tol) << c.name;
    EXPECT_LT(worst_cone, c.cone_tol) << c.name;
    EXPECT_LT(worst_omega3, c.cone_tol * omega_body0.z()) << c.name;
  }
}
