// The second-order gap bound between two stones (contact/pair_gap_bound.h, docs/physics.md
// "The second-order gap bound") checked against physics computed independently: the plane
// contact's force bound against the Newton-Euler solve of every mode (plane_contact_dynamics),
// and the gap bound against the lens-lens distance along integrated plane-contact trajectories.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "virtual_go/body/mass_properties.h"
#include "virtual_go/contact/pair_gap_bound.h"
#include "virtual_go/contact/plane_contact.h"
#include "virtual_go/contact/plane_contact_dynamics.h"
#include "virtual_go/geometry/lens_pair_distance.h"

namespace vg = virtual_go;
using Eigen::Quaterniond;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

const vg::LensShape kShape(0.022, 0.0092);  // size 33
const vg::MassProperties kMass = vg::MassProperties::of_lens(kShape, 2700.0);
const vg::LensGeometry kLens(kShape);
const double kG = 9.80665;

vg::ContactMaterial material() {
  vg::ContactMaterial m;
  m.friction = 0.3;
  m.rolling_resistance_m = 5e-6;
  m.spinning_friction_m = 15e-6;
  return m;
}

vg::MotionModel model() { return vg::MotionModel(vg::MotionModelKind::rigid_body, kMass); }

// A random orientation whose axis is tilted by at most max_tilt from +z or from -z.
Quaterniond tilted(std::mt19937_64& rng, double max_tilt) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double tilt = max_tilt * u(rng), azimuth = 2 * M_PI * u(rng), spin = 2 * M_PI * u(rng);
  Quaterniond q = Quaterniond(Eigen::AngleAxisd(azimuth, Vector3d::UnitZ())) *
                  Quaterniond(Eigen::AngleAxisd(tilt, Vector3d::UnitX())) *
                  Quaterniond(Eigen::AngleAxisd(spin, Vector3d::UnitZ()));
  if (u(rng) < 0.5) q = q * Quaterniond(Eigen::AngleAxisd(M_PI, Vector3d::UnitX()));
  return q.normalized();
}

Vector3d random_vector(std::mt19937_64& rng, double max_norm) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector3d v;
  do {
    v = Vector3d(u(rng), u(rng), u(rng));
  } while (v.norm() > 1.0);
  return max_norm * v;
}

vg::ContactLaw random_law(std::mt19937_64& rng) {
  const int k = std::uniform_int_distribution<int>(0, 2)(rng);
  return k == 0 ? vg::ContactLaw::free : k == 1 ? vg::ContactLaw::sliding : vg::ContactLaw::stuck;
}

Vector3d horizontal_unit(std::mt19937_64& rng) {
  const double a = std::uniform_real_distribution<double>(0.0, 2 * M_PI)(rng);
  return Vector3d(std::cos(a), std::sin(a), 0.0);
}

}  // namespace

TEST(PairGapBound, ReachLiesBelowItsTangents) {
  // The concavity the bound rests on: rho(c) <= rho(c0) + rho'(c0) (c - c0) on [-1, 1].
  double worst = -1.0;
  for (int i = 0; i <= 400; ++i) {
    const double c0 = -1.0 + i / 200.0;
    for (int j = 0; j <= 400; ++j) {
      const double c = -1.0 + j / 200.0;
      worst = std::max(worst, kLens.reach(c) - kLens.reach(c0) - kLens.reach_slope(c0) * (c - c0));
    }
  }
  EXPECT_LE(worst, 1e-17);
}

TEST(PairGapBound, PlaneForceBoundHoldsForEveryModeOfTheNewtonEulerSolve) {
  std::mt19937_64 rng(15);
  const vg::PlaneContactSetup setup{model(), kLens, Vector3d(0, 0, -kG), 0.0, material()};
  const double beta = std::acos(kLens.cos_cap_cone());
  int checked = 0, refused = 0;
  double worst_n = 0.0, worst_f = 0.0, worst_alpha = 0.0;
  for (int k = 0; k < 20000; ++k) {
    const Quaterniond q = tilted(rng, 0.999 * beta);
    const Vector3d b = q * Vector3d::UnitZ();
    vg::PlaneContactMode mode;
    mode.part = kLens.part_towards_plane(b.z());
    mode.tangential.law = random_law(rng);
    mode.rolling.law = random_law(rng);
    mode.spinning.law = random_law(rng);
    mode.tangential.reference_world = horizontal_unit(rng);
    mode.rolling.reference_world = horizontal_unit(rng);
    mode.spinning.reference_world = std::uniform_real_distribution<double>(0, 1)(rng) < 0.5
                                        ? Vector3d(0, 0, 1)
                                        : Vector3d(0, 0, -1);
    const Vector3d v = random_vector(rng, 0.5);
    const Vector3d w = random_vector(rng, 20.0);
    const vg::PlaneContactKinematics kin =
        vg::plane_contact_kinematics(setup, mode, Vector2d(0, 0), q, v.head<2>(), w);
    const vg::PlaneContactForces f = vg::solve_plane_contact(setup, mode, kin);
    if (!f.solved) continue;
    const double n = f.normal_force_n;
    // A stuck part whose force is beyond its law is not the model's mode there.
    if (mode.tangential.law == vg::ContactLaw::stuck &&
        f.friction_force_world.norm() > setup.material.friction * n + 1e-15)
      continue;
    if (mode.rolling.law == vg::ContactLaw::stuck &&
        f.rolling_couple_world.norm() > setup.material.rolling_resistance_m * n + 1e-18)
      continue;
    if (mode.spinning.law == vg::ContactLaw::stuck &&
        std::abs(f.spinning_couple_nm) > setup.material.spinning_friction_m * n + 1e-18)
      continue;
    const double kinetic =
        0.5 * kMass.mass() * kin.velocity_world.squaredNorm() +
        0.5 * kin.angular_velocity_world.dot(kin.inertia_world * kin.angular_velocity_world);
    const auto bound =
        vg::plane_cap_force_bound(setup.model, kLens, setup.material, kG, b, kin.velocity_world,
                                  kin.angular_velocity_world, kinetic);
    if (!bound) {
      ++refused;
      continue;
    }
    ++checked;
    EXPECT_GT(n, 0.0) << "the bound excluded lift-off, sample " << k;
    worst_n = std::max(worst_n, n / bound->normal_force_n);
    const Vector3d force_per_mass = f.linear_acceleration_world - setup.gravity_world;
    worst_f = std::max(worst_f, force_per_mass.norm() / bound->motion.force_per_mass_mps2);
    worst_alpha = std::max(worst_alpha, f.angular_acceleration_world.norm() /
                                            bound->motion.angular_acceleration_radps2);
  }
  std::printf(
      "plane force bound: %d states checked, %d refused; largest N/bound %.3f, |F|/m/bound "
      "%.3f, |alpha|/bound %.3f\n",
      checked, refused, worst_n, worst_f, worst_alpha);
  EXPECT_GT(checked, 5000);
  EXPECT_LE(worst_n, 1.0);
  EXPECT_LE(worst_f, 1.0);
  EXPECT_LE(worst_alpha, 1.0);
}

namespace {

// A stone on the plane z = 0 touching with its cap, in plane contact.
vg::RigidBodyState on_plane(const Vector3d& xy, const Quaterniond& q, const Vector3d& v,
                            const Vector3d& w) {
  vg::RigidBodyState s;
  s.orientation = q;
  const Vector3d b = q * Vector3d::UnitZ();
  s.position_world = Vector3d(xy.x(), xy.y(), kLens.reach(b.z()));
  s.velocity_world = Vector3d(v.x(), v.y(), 0.0);
  // The contact point's normal velocity must vanish: v_z = -(omega x r)_z at the contact point.
  const vg::LensPose pose{s.position_world, b};
  const Vector3d contact = vg::lens_support_world(kLens, pose, Vector3d::UnitZ());
  s.velocity_world.z() = -w.cross(contact - s.position_world).z();
  s.angular_momentum_world = model().angular_momentum_world(q, w);
  return s;
}

}  // namespace

TEST(PairGapBound, NeverAboveTheDistanceAlongPlaneContactTrajectories) {
  std::mt19937_64 rng(1515);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double beta = std::acos(kLens.cos_cap_cone());
  const vg::PlaneRegion region = vg::PlaneRegion::inside(Vector2d::Zero(), Vector2d(0.5, 0.5));
  vg::PlaneContactOptions options;
  int trajectories = 0, samples = 0;
  double smallest_margin = 1.0, budget_used = 0.0, log_step_ratio = 0.0;
  for (int k = 0; k < 300 && trajectories < 120; ++k) {
    const bool both_move = k % 2 == 0;
    const vg::RigidBodyState a = on_plane(Vector3d::Zero(), tilted(rng, 0.3 * beta),
                                          random_vector(rng, 0.3), random_vector(rng, 12.0));
    const Vector3d dir = horizontal_unit(rng);
    vg::RigidBodyState b = on_plane(0.023 * dir, tilted(rng, 0.3 * beta),
                                    both_move ? random_vector(rng, 0.3) : Vector3d::Zero(),
                                    both_move ? random_vector(rng, 12.0) : Vector3d::Zero());
    // Slide B horizontally until the gap is the target (1 nm .. 10 um, log-uniform).
    const double target = std::pow(10.0, -9.0 + 4.0 * u(rng));
    vg::LensPairContact c;
    for (int it = 0; it < 30; ++it) {
      c = vg::lens_pair_distance(kLens, vg::lens_pose(a), kLens, vg::lens_pose(b));
      const Vector3d nh(c.normal_world.x(), c.normal_world.y(), 0.0);
      if (nh.norm() < 0.2) break;
      b.position_world += (target - c.gap_m) / nh.squaredNorm() * nh;
      if (std::abs(c.gap_m - target) < 1e-3 * target) break;
    }
    if (!(std::abs(c.gap_m - target) < 1e-2 * target)) continue;
    const vg::MotionModel m = model();
    const auto motion = [&](const vg::RigidBodyState& s) -> std::optional<vg::GapBoundMotion> {
      const Vector3d w = m.angular_velocity_world(s.orientation, s.angular_momentum_world);
      if (w.norm() == 0.0 && s.velocity_world.norm() == 0.0) return vg::still_motion();
      // Energy above the lens lying flat: the kinetic energy bound of the whole phase.
      const double kinetic = 0.5 * kMass.mass() * s.velocity_world.squaredNorm() +
                             0.5 * w.dot(s.angular_momentum_world) +
                             kMass.mass() * kG * (s.position_world.z() - kLens.half_height());
      const auto bound =
          vg::plane_cap_force_bound(m, kLens, material(), kG, s.orientation * Vector3d::UnitZ(),
                                    s.velocity_world, w, kinetic);
      if (!bound) return std::nullopt;
      return bound->motion;
    };
    const auto ma = motion(a), mb = motion(b);
    if (!ma || !mb) continue;
    const vg::PairGapBound bound(kLens, vg::lens_pose(a), *ma, kLens, vg::lens_pose(b), *mb,
                                 c.normal_world, Vector3d::Zero());
    std::optional<vg::PlaneContact> pa, pb;
    try {
      pa.emplace(m, kLens, Vector3d(0, 0, -kG), 0.0, region, material(), a, 0.0, options);
      if (both_move)
        pb.emplace(m, kLens, Vector3d(0, 0, -kG), 0.0, region, material(), b, 0.0, options);
    } catch (const std::exception&) {
      continue;
    }
    // Sample past the bound's zero (where it says nothing any more), within its validity.
    const double horizon = std::min({bound.valid_for(), 3.0 * bound.time_to(0.0) + 1e-6, 0.05});
    ++trajectories;
    const double speed = (a.velocity_world - b.velocity_world).norm() +
                         kLens.half_width() * (ma->angular_speed_radps + mb->angular_speed_radps);
    log_step_ratio += std::log(bound.time_to(0.5e-9) / ((target - 0.5e-9) / speed));
    for (int s = 1; s <= 400; ++s) {
      const double t = horizon * s / 400.0;
      const vg::PlaneContactOutcome oa = pa->advance(t);
      EXPECT_NE(oa.event, vg::PlaneContactEvent::lift_off);
      vg::RigidBodyState sb = b;
      if (pb) {
        const vg::PlaneContactOutcome ob = pb->advance(t);
        EXPECT_NE(ob.event, vg::PlaneContactEvent::lift_off);
        sb = pb->state_at(std::min(t, pb->time_reached()));
      }
      const vg::RigidBodyState sa = pa->state_at(std::min(t, pa->time_reached()));
      const double gap =
          vg::lens_pair_distance(kLens, vg::lens_pose(sa), kLens, vg::lens_pose(sb)).gap_m;
      const double lower = bound.lower_bound(t);
      ++samples;
      // The integrator's tolerance (1e-14 absolute) is the round-off of the trajectory itself.
      EXPECT_GE(gap, lower - 1e-13) << "trajectory " << k << " at t = " << t;
      smallest_margin = std::min(smallest_margin, gap - lower);
      // The share of the curvature budget A tau^2 / 2 the true gap used.
      const double budget = -0.5 * bound.curvature() * t * t;
      if (budget > 0.0)
        budget_used = std::max(budget_used, (bound.gap() + bound.rate() * t - gap) / budget);
    }
  }
  std::printf(
      "gap bound: %d trajectories, %d samples; smallest distance - bound %.3g m; at most %.3f of "
      "the curvature budget used; the second-order step is %.0f times the first-order one "
      "(geometric mean)\n",
      trajectories, samples, smallest_margin, budget_used,
      std::exp(log_step_ratio / std::max(1, trajectories)));
  EXPECT_GE(trajectories, 60);
  EXPECT_LE(budget_used, 1.0);
}
