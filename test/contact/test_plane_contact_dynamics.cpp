// Contact forces of a stone on a plane against physics: statics, the steady rim rolling of
// Euler's disk type, the power balance (contact forces only dissipate, and exactly at the rate
// of each sliding law), and the constraints (gap acceleration from the reach function,
// stuck velocities with zero rate by finite differences).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "virtual_go/body/mass_properties.h"
#include "virtual_go/contact/lens_on_plane.h"
#include "virtual_go/contact/plane_contact_dynamics.h"

namespace vg = virtual_go;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

const vg::LensShape kShape(0.022, 0.0092);  // size 33
const vg::MassProperties kMass = vg::MassProperties::of_lens(kShape, 2700.0);
const double kG = 9.80665;

vg::PlaneContactSetup make_setup(double mu = 0.3, double l_r = 5e-6, double l_s = 15e-6) {
  vg::ContactMaterial material;
  material.friction = mu;
  material.rolling_resistance_m = l_r;
  material.spinning_friction_m = l_s;
  return {vg::MotionModel(vg::MotionModelKind::rigid_body, kMass), vg::LensGeometry(kShape),
          Vector3d(0, 0, -kG), 0.0, material};
}

vg::PlaneContactMode mode_of(vg::LensPart part, vg::ContactLaw t, vg::ContactLaw r,
                             vg::ContactLaw s) {
  vg::PlaneContactMode m;
  m.part = part;
  m.tangential.law = t;
  m.rolling.law = r;
  m.spinning.law = s;
  m.tangential.reference_world = m.rolling.reference_world = Vector3d::UnitX();
  m.spinning.reference_world = Vector3d::UnitZ();
  return m;
}

// A random state on a cap or the rim (orientation uniform, slip ~0.3 m/s, spin ~20 rad/s) in mode
// i % 27 (tangential, rolling and spinning each free, sliding or stuck), each sliding law along
// the present motion.
std::pair<vg::PlaneContactMode, vg::PlaneContactKinematics> random_mode_state(
    const vg::PlaneContactSetup& setup, int i, std::mt19937& rng) {
  std::normal_distribution<double> n;
  const Eigen::Quaterniond q = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
  const Vector3d b = q * Vector3d::UnitZ();
  const vg::ContactLaw laws[3] = {vg::ContactLaw::free, vg::ContactLaw::sliding,
                                  vg::ContactLaw::stuck};
  auto mode = mode_of(setup.lens.part_towards_plane(b.z()), laws[i % 3], laws[(i / 3) % 3],
                      laws[(i / 9) % 3]);
  const Vector2d v(0.3 * n(rng), 0.3 * n(rng));
  const Vector3d omega(20 * n(rng), 20 * n(rng), 20 * n(rng));
  const auto k0 = vg::plane_contact_kinematics(setup, mode, Vector2d::Zero(), q, v, omega);
  mode.tangential.reference_world = k0.slip_velocity().normalized();
  mode.rolling.reference_world = k0.rolling_velocity().normalized();
  mode.spinning.reference_world = Vector3d(0, 0, k0.spin_velocity() > 0 ? 1 : -1);
  return {mode, vg::plane_contact_kinematics(setup, mode, Vector2d::Zero(), q, v, omega)};
}

// Power of all forces but gravity: dE/dt from the accelerations, E = 1/2 m v^2 + 1/2 w.Iw - m g.x.
double energy_rate(const vg::PlaneContactSetup& s, const vg::PlaneContactKinematics& k,
                   const vg::PlaneContactForces& f) {
  const double m = s.model.mass_properties().mass();
  const Vector3d& w = k.angular_velocity_world;
  const Vector3d l_dot =
      k.inertia_world * f.angular_acceleration_world + w.cross(k.inertia_world * w);
  return m * k.velocity_world.dot(f.linear_acceleration_world - s.gravity_world) + w.dot(l_dot);
}

}  // namespace

TEST(PlaneContactDynamics, FlatStoneAtRestCarriesItsWeight) {
  const auto setup = make_setup();
  for (vg::ContactLaw law : {vg::ContactLaw::free, vg::ContactLaw::stuck}) {
    const auto mode = mode_of(vg::LensPart::bottom_cap, law, law, law);
    const auto k = vg::plane_contact_kinematics(setup, mode, Vector2d(0.01, -0.02),
                                                Eigen::Quaterniond::Identity(), Vector2d::Zero(),
                                                Vector3d::Zero());
    EXPECT_NEAR(k.position_world.z(), 0.0046, 1e-17);  // G is c above the plane
    const auto f = vg::solve_plane_contact(setup, mode, k);
    ASSERT_TRUE(f.solved);
    EXPECT_NEAR(f.normal_force_n, kMass.mass() * kG, 1e-15);
    EXPECT_LT(f.friction_force_world.norm(), 1e-18);
    EXPECT_LT(f.linear_acceleration_world.norm(), 1e-14);
    EXPECT_LT(f.angular_acceleration_world.norm(), 1e-10);
  }
}

TEST(PlaneContactDynamics, SlidingFlatStoneDeceleratesAtMuG) {
  const auto setup = make_setup(0.3, 0.0, 0.0);
  const auto mode = mode_of(vg::LensPart::bottom_cap, vg::ContactLaw::sliding, vg::ContactLaw::free,
                            vg::ContactLaw::free);
  const Vector2d v(0.3, -0.4);
  const auto k = vg::plane_contact_kinematics(setup, mode, Vector2d::Zero(),
                                              Eigen::Quaterniond::Identity(), v, Vector3d::Zero());
  const auto f = vg::solve_plane_contact(setup, mode, k);
  ASSERT_TRUE(f.solved);
  // Flat and not turning: the friction's torque about G tilts the stone, but at this instant the
  // centre's vertical acceleration is still zero, so N = m g and a_t = -mu g v/|v|.
  EXPECT_NEAR(f.normal_force_n, kMass.mass() * kG, 1e-15);
  const Vector3d expected = -0.3 * kG * Vector3d(v.x(), v.y(), 0).normalized();
  EXPECT_LT((f.linear_acceleration_world - expected).norm(), 1e-14);
  // Friction acts c below G: the torque pitches the stone forward (about e_z x v).
  const Vector3d forward_axis = Vector3d::UnitZ().cross(Vector3d(v.x(), v.y(), 0)).normalized();
  const double c = 0.0046;
  EXPECT_NEAR(f.angular_acceleration_world.dot(forward_axis),
              c * 0.3 * kMass.mass() * kG / kMass.principal_moments_body().x(), 1e-9);
}

TEST(PlaneContactDynamics, RimRollingInPlaceNeedsOnlyTheWeight) {
  // Axis tilted by alpha from the vertical, omega = Omega (e_z - cos(alpha) b), Omega^2 sin(alpha)
  // = m g a / I1: the centre stays put, so N = m g and no friction; dL/dt = I1 Omega^2 sin(alpha)
  // e_z x e.
  const auto setup = make_setup();
  const double m = kMass.mass(), i1 = kMass.principal_moments_body().x(), a = 0.011;
  for (double alpha_deg : {50.0, 60.0, 75.0}) {
    const double alpha = alpha_deg * M_PI / 180;
    const double omega_rate = std::sqrt(m * kG * a / (i1 * std::sin(alpha)));
    const Eigen::Quaterniond q(Eigen::AngleAxisd(alpha, Vector3d::UnitY()));
    const Vector3d b = q * Vector3d::UnitZ();
    const Vector3d e = (Vector3d::UnitZ() - b.z() * b).normalized();
    const Vector3d omega = omega_rate * (Vector3d::UnitZ() - std::cos(alpha) * b);
    const auto mode = mode_of(vg::LensPart::rim, vg::ContactLaw::stuck, vg::ContactLaw::free,
                              vg::ContactLaw::free);
    const auto k =
        vg::plane_contact_kinematics(setup, mode, Vector2d::Zero(), q, Vector2d::Zero(), omega);
    EXPECT_LT(k.velocity_world.norm(), 1e-15);
    const auto f = vg::solve_plane_contact(setup, mode, k);
    ASSERT_TRUE(f.solved);
    EXPECT_NEAR(f.normal_force_n, m * kG, 1e-12 * m * kG) << alpha_deg;
    EXPECT_LT(f.friction_force_world.norm(), 1e-12 * m * kG) << alpha_deg;
    EXPECT_LT(f.linear_acceleration_world.norm(), 1e-11) << alpha_deg;
    const Vector3d l_dot =
        k.inertia_world * f.angular_acceleration_world + omega.cross(k.inertia_world * omega);
    const Vector3d expected =
        i1 * omega_rate * omega_rate * std::sin(alpha) * Vector3d::UnitZ().cross(e);
    EXPECT_LT((l_dot - expected).norm(), 1e-12 * expected.norm()) << alpha_deg;
  }
}

TEST(PlaneContactDynamics, ContactForcesDissipateExactlyAtTheSlidingLawsRate) {
  // dE/dt = F . u + omega . tau: zero for stuck and free parts, -mu N |u_t|, -l_r N |omega_t|,
  // -l_s N |omega_z| for sliding ones. Random states on caps and rim, every mode.
  const auto setup = make_setup(0.4, 20e-6, 30e-6);
  const double m = kMass.mass();
  std::mt19937 rng(17);
  int checked = 0;
  double worst = 0.0;
  for (int i = 0; i < 3000; ++i) {
    const auto [mode, k] = random_mode_state(setup, i, rng);
    const auto f = vg::solve_plane_contact(setup, mode, k);
    ASSERT_TRUE(f.solved);
    const double nf = f.normal_force_n;
    double expected = 0.0;
    if (mode.tangential.law == vg::ContactLaw::sliding)
      expected -= 0.4 * nf * k.slip_velocity().norm();
    if (mode.rolling.law == vg::ContactLaw::sliding)
      expected -= 20e-6 * nf * k.rolling_velocity().norm();
    if (mode.spinning.law == vg::ContactLaw::sliding)
      expected -= 30e-6 * nf * std::abs(k.spin_velocity());
    const double scale = m * kG * (1.0 + k.velocity_world.norm()) + nf * 0.4 * 1.0;
    worst = std::max(worst, std::abs(energy_rate(setup, k, f) - expected) / scale);
    ++checked;
  }
  EXPECT_EQ(checked, 3000);
  EXPECT_LT(worst, 1e-12);
}

TEST(PlaneContactDynamics, ConstraintsHoldAtTheAccelerationLevel) {
  // The gap's second derivative vanishes: a_z = rho'(b_z) b_z'' + rho''(b_z) b_z'^2, with
  // b'' = alpha x b + omega x (omega x b) (reach slope and curvature from the lens geometry).
  // Stuck velocities have zero rate: the slip velocity's rate by central differences of the
  // kinematics along the motion (offsets recomputed from the geometry, not from dr/dt).
  const auto setup = make_setup(1.0, 1e-3, 1e-3);
  std::mt19937 rng(23);
  std::normal_distribution<double> n;
  double worst_gap = 0.0, worst_slip = 0.0, worst_spin = 0.0;
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Quaterniond q = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    const Vector3d b = q * Vector3d::UnitZ();
    vg::PlaneContactMode mode;
    mode.part = setup.lens.part_towards_plane(b.z());
    mode.tangential.law = vg::ContactLaw::stuck;
    mode.rolling.law = i % 2 ? vg::ContactLaw::stuck : vg::ContactLaw::free;
    mode.spinning.law = i % 4 < 2 ? vg::ContactLaw::stuck : vg::ContactLaw::free;
    const Vector3d omega(10 * n(rng), 10 * n(rng), 10 * n(rng));
    const auto k =
        vg::plane_contact_kinematics(setup, mode, Vector2d::Zero(), q, Vector2d::Zero(), omega);
    const auto f = vg::solve_plane_contact(setup, mode, k);
    ASSERT_TRUE(f.solved);
    const Vector3d& w = k.angular_velocity_world;
    const Vector3d b_dot = w.cross(b);
    const Vector3d b_ddot = f.angular_acceleration_world.cross(b) + w.cross(b_dot);
    const double a_z = setup.lens.reach_slope(b.z()) * b_ddot.z() +
                       setup.lens.reach_curvature(b.z()) * b_dot.z() * b_dot.z();
    worst_gap = std::max(worst_gap, std::abs(f.linear_acceleration_world.z() - a_z) / kG);
    // Slip velocity along the motion: v(t) = v + a t, omega(t) = omega + alpha t, q(t) turned by
    // the mean omega; u_t(t) = (v + omega x r(q))_t.
    auto slip_at = [&](double t) {
      const Vector3d wt = w + t * f.angular_acceleration_world;
      const Vector3d turn = (w + 0.5 * t * f.angular_acceleration_world) * t;
      const Eigen::Quaterniond qt =
          Eigen::Quaterniond(Eigen::AngleAxisd(turn.norm(), turn.normalized())) * q;
      const Vector3d r =
          vg::plane_contact_offset_world(setup.lens, mode.part, qt * Vector3d::UnitZ());
      const Vector3d u = k.velocity_world + t * f.linear_acceleration_world + wt.cross(r);
      return Vector3d(u.x(), u.y(), 0.0);
    };
    const double h = 1e-6;
    const Vector3d slip_rate = (slip_at(h) - slip_at(-h)) / (2 * h);
    worst_slip = std::max(worst_slip, slip_rate.norm() / (kG + w.squaredNorm() * 0.011));
    if (mode.spinning.law == vg::ContactLaw::stuck) {
      worst_spin = std::max(worst_spin, std::abs(f.angular_acceleration_world.z()));
    }
  }
  EXPECT_LT(worst_gap, 1e-12);
  EXPECT_LT(worst_slip, 1e-7);
  EXPECT_LT(worst_spin, 1e-9);
}

TEST(PlaneContactDynamics, ForcesSatisfyNewtonEulerTheConstraintsAndTheLawsInEveryMode) {
  // The defining equations, checked one by one on random states of caps and rim in all 27 modes
  // (together they fix the solution): m a = m g + F and I_w alpha + omega x I_w omega = r x F + C
  // from the reported forces; the gap's acceleration p_z = 0, p_t = 0 when the slip is stuck,
  // alpha_t = 0 and alpha_z = 0 when rolling and spinning are stuck (p = a + alpha x r +
  // omega x dr/dt); sliding parts at their bound against the law's direction, free parts zero.
  const double mu = 0.4, l_r = 20e-6, l_s = 30e-6;
  const auto setup = make_setup(mu, l_r, l_s);
  const double m = kMass.mass();
  std::mt19937 rng(29);
  double worst_motion = 0.0, worst_constraint = 0.0, worst_law = 0.0;
  for (int i = 0; i < 2700; ++i) {
    const auto [mode, k] = random_mode_state(setup, i, rng);
    const auto f = vg::solve_plane_contact(setup, mode, k);
    ASSERT_TRUE(f.solved);
    const Vector3d& w = k.angular_velocity_world;
    const Vector3d& r = k.offset_world;
    const double nf = f.normal_force_n;
    const Vector3d force = nf * Vector3d::UnitZ() + f.friction_force_world;
    const Vector3d couple = f.rolling_couple_world + f.spinning_couple_nm * Vector3d::UnitZ();
    const Vector3d& a = f.linear_acceleration_world;
    const Vector3d& alpha = f.angular_acceleration_world;
    // Scales: forces by m g, moments by m g |r|, accelerations by g and g / |r|.
    const double force_scale = m * kG + std::abs(nf), moment_scale = force_scale * 0.011;
    worst_motion =
        std::max(worst_motion, (m * a - m * setup.gravity_world - force).norm() / force_scale);
    const Vector3d moment_residual =
        k.inertia_world * alpha + w.cross(k.inertia_world * w) - r.cross(force) - couple;
    worst_motion = std::max(worst_motion, moment_residual.norm() / moment_scale);
    const Vector3d p = a + alpha.cross(r) + w.cross(k.offset_rate_world);
    const double accel_scale = kG + w.squaredNorm() * 0.011;
    worst_constraint = std::max(worst_constraint, std::abs(p.z()) / accel_scale);
    if (mode.tangential.law == vg::ContactLaw::stuck)
      worst_constraint = std::max(worst_constraint, p.head<2>().norm() / accel_scale);
    if (mode.rolling.law == vg::ContactLaw::stuck)
      worst_constraint = std::max(worst_constraint, alpha.head<2>().norm() * 0.011 / accel_scale);
    if (mode.spinning.law == vg::ContactLaw::stuck)
      worst_constraint = std::max(worst_constraint, std::abs(alpha.z()) * 0.011 / accel_scale);
    // The laws: sliding opposes the motion's direction at its bound, free is zero.
    auto law_error = [&](vg::ContactLaw law, const Vector3d& value, const Vector3d& bound_value,
                         double scale) {
      if (law == vg::ContactLaw::sliding) return (value - bound_value).norm() / scale;
      if (law == vg::ContactLaw::free) return value.norm() / scale;
      return 0.0;
    };
    worst_law =
        std::max(worst_law, law_error(mode.tangential.law, f.friction_force_world,
                                      -mu * nf * k.slip_velocity().normalized(), force_scale));
    worst_law =
        std::max(worst_law, law_error(mode.rolling.law, f.rolling_couple_world,
                                      -l_r * nf * k.rolling_velocity().normalized(), moment_scale));
    worst_law =
        std::max(worst_law, law_error(mode.spinning.law, Vector3d(0, 0, f.spinning_couple_nm),
                                      Vector3d(0, 0, -l_s * nf * (k.spin_velocity() > 0 ? 1 : -1)),
                                      moment_scale));
  }
  std::printf("[ measured ] worst relative residual: motion %.3g, constraints %.3g, laws %.3g\n",
              worst_motion, worst_constraint, worst_law);
  EXPECT_LT(worst_motion, 1e-13);
  EXPECT_LT(worst_constraint, 1e-13);
  EXPECT_LT(worst_law, 1e-14);
}
