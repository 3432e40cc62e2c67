// The joint solve's rows and iteration (src/world/nonsmooth_island_joint.cpp) checked against the
// contact laws themselves: for a sub-step's velocities, the answer must satisfy Signorini's
// condition and Coulomb's law at every contact (normal impulse >= 0, no approach, no impulse where
// the contact opens; friction inside the cone where the contact sticks and against the slip on its
// circle where it slides; each couple within l times the normal impulse and against the rotation
// where it saturates), remove no more than it may (the kinetic energy never rises), and give a lone
// stone's closed form. The post-solve velocities are computed here from the rows' arms, not with
// the solver's own functions.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "../../src/world/nonsmooth_island_impl.h"

namespace {

namespace detail = virtual_go::nonsmooth_island_detail;
using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kMassKg = 0.0055;         // a size-33 slate stone, about
constexpr double kHalfWidthM = 0.0111;     // a
constexpr double kHalfHeightM = 0.0046;    // c (centre to the bottom point, flat)
constexpr double kStepS = 2.5e-4;          // the island's sub-step h
constexpr double kRollingM = 5e-5;         // l_r, the demo's
constexpr double kSpinningM = 1e-4;        // l_s
const Vector3d kGravity(0.0, 0.0, -9.81);  // m/s^2

// A sub-step's velocity problem: bodies (free velocities after h of gravity, at rest before) and
// their contact rows (board rows with a = -1).
struct Problem {
  std::vector<virtual_go::RigidBodyState> states;
  std::vector<double> inverse_mass;
  std::vector<Matrix3d> inverse_inertia, inertia;
  std::vector<Vector3d> velocity, angular_velocity;  // before the solve
  std::vector<detail::SolveRow> rows;

  void add_body(const Vector3d& position) {
    virtual_go::RigidBodyState s;
    s.position_world = position;
    states.push_back(s);
    // A lens's moments: about a diameter m (a^2 / 4 + c^2 / 3), about its axis m a^2 / 2, roughly.
    const double across =
        kMassKg * (kHalfWidthM * kHalfWidthM / 4 + kHalfHeightM * kHalfHeightM / 3);
    const double about_axis = kMassKg * kHalfWidthM * kHalfWidthM / 2;
    inertia.push_back(Vector3d(across, across, about_axis).asDiagonal());
    inverse_inertia.push_back(inertia.back().inverse());
    inverse_mass.push_back(1.0 / kMassKg);
    velocity.push_back(kGravity * kStepS);
    angular_velocity.push_back(Vector3d::Zero());
  }
  Vector3d point_velocity(int i, const Vector3d& point) const {
    if (i < 0) return Vector3d::Zero();
    return velocity[i] + angular_velocity[i].cross(point - states[i].position_world);
  }
  // A row between a (-1: the board) and b at `point`, the normal from a to b.
  void add_row(int a, int b, const Vector3d& normal, const Vector3d& point, double mu,
               bool couples) {
    detail::SolveRow r =
        detail::make_row(a, b, normal, point, mu, states, inverse_mass, inverse_inertia);
    r.u0 = point_velocity(b, point) - point_velocity(a, point);
    r.w0 = angular_velocity[b] - (a >= 0 ? angular_velocity[a] : Vector3d::Zero());
    r.key = static_cast<long>(rows.size());
    if (couples) {
      r.rolling_m = kRollingM;
      r.spinning_m = kSpinningM;
    }
    rows.push_back(r);
  }
  double kinetic_energy(const std::vector<Vector3d>& dv, const std::vector<Vector3d>& dw) const {
    double e = 0.0;
    for (std::size_t i = 0; i < states.size(); ++i) {
      const Vector3d v = velocity[i] + dv[i], w = angular_velocity[i] + dw[i];
      e += 0.5 * kMassKg * v.squaredNorm() + 0.5 * w.dot(inertia[i] * w);
    }
    return e;
  }
};

struct Solved {
  std::vector<Vector3d> dv, dw;
  int iterations = 0;
};

Solved solve(Problem& p, bool active_set_steps = true) {
  Solved s;
  s.dv.assign(p.states.size(), Vector3d::Zero());
  s.dw.assign(p.states.size(), Vector3d::Zero());
  s.iterations = detail::solve_rows(p.rows, s.dv, s.dw, 0.0, active_set_steps);
  return s;
}

// Every row's impulses against its law, with the velocities after the solve computed here.
// `speed_tolerance`: m/s (and rad/s times the lever) within which a motion counts as none.
void expect_laws_hold(const Problem& p, const Solved& s, double speed_tolerance) {
  const auto after = [&](int i, const Vector3d& point) {
    if (i < 0) return Vector3d(Vector3d::Zero());
    return Vector3d(p.velocity[i] + s.dv[i] +
                    (p.angular_velocity[i] + s.dw[i]).cross(point - p.states[i].position_world));
  };
  const auto turning = [&](int i) {
    if (i < 0) return Vector3d(Vector3d::Zero());
    return Vector3d(p.angular_velocity[i] + s.dw[i]);
  };
  for (std::size_t k = 0; k < p.rows.size(); ++k) {
    const detail::SolveRow& r = p.rows[k];
    const Vector3d point = p.states[r.b].position_world + r.rb;
    const Vector3d u = after(r.b, point) - after(r.a, point);
    const double u_n = u.dot(r.normal);
    // Signorini: no approach; an impulse only where the contact stays closed.
    EXPECT_GE(r.lambda_n, 0.0) << "row " << k;
    EXPECT_GE(u_n, -speed_tolerance) << "row " << k;
    if (r.lambda_n > 0.0) {
      EXPECT_LE(u_n, speed_tolerance) << "row " << k;
    }
    // Coulomb: inside the cone; sticking without slip, sliding against the slip.
    const Eigen::Vector2d lt(r.lambda_1, r.lambda_2);
    const Eigen::Vector2d ut(u.dot(r.t1), u.dot(r.t2));
    const double limit = r.mu * r.lambda_n;
    EXPECT_LE(lt.norm(), limit * (1 + 1e-12)) << "row " << k;
    if (lt.norm() < limit * (1 - 1e-6)) {
      EXPECT_LE(ut.norm(), speed_tolerance) << "row " << k << " sticks but slips";
    } else if (limit > 0.0 && ut.norm() > speed_tolerance) {
      // On the circle, the slip exactly opposite the impulse (maximal dissipation): against it,
      // and its part across the impulse no motion (within the speed tolerance, as every motion
      // here; an angle would ask more of a slow slip than of a fast one).
      const double across = std::abs(ut.x() * lt.y() - ut.y() * lt.x()) / lt.norm();
      EXPECT_LT(ut.dot(lt), 0.0) << "row " << k << " slides with its friction";
      EXPECT_LE(across, speed_tolerance) << "row " << k << " slides off its law";
    }
    // The couples, each within l lambda_n (a box), opposing the rotation where saturated.
    const Vector3d w = turning(r.b) - turning(r.a);
    const Vector3d axes[3] = {r.t1, r.t2, r.normal};
    for (int c = 0; c < 3; ++c) {
      const double l = c < 2 ? r.rolling_m : r.spinning_m;
      const double cap = l * r.lambda_n;
      const double w_c = w.dot(axes[c]) * kHalfWidthM;  // as a rim speed
      EXPECT_LE(std::abs(r.couple[c]), cap * (1 + 1e-12)) << "row " << k;
      if (std::abs(r.couple[c]) < cap * (1 - 1e-6)) {
        EXPECT_LE(std::abs(w_c), speed_tolerance) << "row " << k << " couple " << c;
      } else if (cap > 0.0 && std::abs(w_c) > speed_tolerance) {
        EXPECT_LT(w_c * r.couple[c], 0.0) << "row " << k << " couple " << c;
      }
    }
  }
}

TEST(NonsmoothIslandJoint, ALoneFlatStoneLosesExactlyItsSubStepOfFall) {
  // One stone flat on the board: the board's impulse is m g h, nothing else acts, and the stone
  // ends still.
  Problem p;
  p.add_body(Vector3d(0.0, 0.0, kHalfHeightM));
  p.add_row(-1, 0, Vector3d::UnitZ(), Vector3d::Zero(), 0.3, true);
  const Solved s = solve(p);
  const double m_g_h = kMassKg * 9.81 * kStepS;
  EXPECT_NEAR(p.rows[0].lambda_n, m_g_h, 1e-12 * m_g_h);
  EXPECT_NEAR(Eigen::Vector2d(p.rows[0].lambda_1, p.rows[0].lambda_2).norm(), 0.0, 1e-15 * m_g_h);
  EXPECT_LE((p.velocity[0] + s.dv[0]).norm(), 1e-12 * 9.81 * kStepS);
  EXPECT_LE(s.dw[0].norm(), 1e-9);
}

// A stone lying in the groove between two stones that lie on the board: its rims rest on theirs
// with normals `slope` below the horizontal, every contact with friction mu and the board's
// couples.
Problem groove(double slope_rad, double mu, const Vector3d& upper_velocity,
               const Vector3d& upper_angular_velocity) {
  Problem p;
  const double spread = 0.018;  // the lower stones' centres at -+spread
  p.add_body(Vector3d(-spread, 0.0, kHalfHeightM));
  p.add_body(Vector3d(spread, 0.0, kHalfHeightM));
  // The upper stone's centre above the origin, its contact points on the lines to the lower
  // centres' rims (the geometry is the problem's, not a lens's: what matters is the normals).
  p.add_body(Vector3d(0.0, 0.0, kHalfHeightM + spread * std::tan(slope_rad)));
  p.velocity[2] += upper_velocity;
  p.angular_velocity[2] = upper_angular_velocity;
  for (int i = 0; i < 2; ++i) {
    p.add_row(-1, i, Vector3d::UnitZ(),
              p.states[i].position_world - kHalfHeightM * Vector3d::UnitZ(), mu, true);
  }
  for (int i = 0; i < 2; ++i) {
    const Vector3d from_lower =
        (p.states[2].position_world - p.states[i].position_world).normalized();
    const Vector3d point = 0.5 * (p.states[2].position_world + p.states[i].position_world);
    p.add_row(i, 2, from_lower, point, mu, false);
  }
  return p;
}

TEST(NonsmoothIslandJoint, AStoneInAGrooveObeysEveryContactLawAndNeverGainsEnergy) {
  // Steep grooves (pair normals 35-45 deg from the horizontal, the slopes of the piles in which
  // plain Gauss-Seidel converged at 0.998 per sweep) and a shallow one, the upper stone at rest
  // (held, or falling on) or sliding along the groove and spinning (friction across the plane of
  // symmetry, where a rocking stone's anisotropic compliance turns a radially clamped impulse away
  // from the slip).
  struct Motion {
    Vector3d velocity_mps, angular_velocity_radps;
  };
  for (const Motion& motion : {Motion{Vector3d::Zero(), Vector3d::Zero()},
                               Motion{Vector3d(0.0, 0.02, 0.0), Vector3d(0.0, 0.0, 3.0)}}) {
    for (const double slope_deg : {10.0, 35.0, 40.0, 45.0}) {
      for (const double mu : {0.1, 0.3, 0.6}) {
        Problem p =
            groove(slope_deg * M_PI / 180, mu, motion.velocity_mps, motion.angular_velocity_radps);
        const std::vector<Vector3d> zero(p.states.size(), Vector3d::Zero());
        const double before = p.kinetic_energy(zero, zero);
        const Solved s = solve(p);
        SCOPED_TRACE(testing::Message() << "slope " << slope_deg << " deg, mu " << mu << ", moving "
                                        << motion.velocity_mps.norm());
        EXPECT_LT(s.iterations, detail::kMaxJointIterations);
        // Converged to 1e-9 of the fastest contact speed per sweep: the laws hold to a small
        // multiple of that.
        const double scale_mps =
            std::max(9.81 * kStepS, motion.velocity_mps.norm() +
                                        kHalfWidthM * motion.angular_velocity_radps.norm());
        expect_laws_hold(p, s, 1e-7 * scale_mps);
        EXPECT_LE(p.kinetic_energy(s.dv, s.dw), before);
        std::printf(
            "[ groove  ] slope %2.0f deg, mu %.1f, along the groove %.2f m/s: %3d iterations, the "
            "upper stone falls on at %.3g of g h\n",
            slope_deg, mu, motion.velocity_mps.norm(), s.iterations,
            -(p.velocity[2] + s.dv[2]).z() / (9.81 * kStepS));
      }
    }
  }
}

// A pyramid of leaning stones, `base` of them on the board in a row touching rim to rim, each
// layer above lying in the grooves of the one below with pair normals `slope` above the
// horizontal, and touching its neighbours in its layer (the cluster of benchmark/many's shape: in
// such wedges the sweeps converge at about 0.995 per sweep). The top stone moves at `top_velocity`
// and turns at `top_angular_velocity`.
Problem pyramid(int base, double slope_rad, double mu, const Vector3d& top_velocity,
                const Vector3d& top_angular_velocity) {
  Problem p;
  std::vector<std::vector<int>> layers;
  for (int layer = 0; layer < base; ++layer) {
    layers.emplace_back();
    const int count = base - layer;
    for (int k = 0; k < count; ++k) {
      const double x = (2 * k - (count - 1)) * kHalfWidthM;
      const double z = kHalfHeightM + layer * kHalfWidthM * std::tan(slope_rad);
      layers.back().push_back(static_cast<int>(p.states.size()));
      p.add_body(Vector3d(x, 0.0, z));
    }
  }
  const int top = layers.back().back();
  p.velocity[top] += top_velocity;
  p.angular_velocity[top] = top_angular_velocity;
  for (const int i : layers.front()) {
    p.add_row(-1, i, Vector3d::UnitZ(),
              p.states[i].position_world - kHalfHeightM * Vector3d::UnitZ(), mu, true);
  }
  const auto touch = [&](int a, int b) {
    const Vector3d normal = (p.states[b].position_world - p.states[a].position_world).normalized();
    p.add_row(a, b, normal, 0.5 * (p.states[a].position_world + p.states[b].position_world), mu,
              false);
  };
  for (std::size_t layer = 0; layer < layers.size(); ++layer) {
    for (std::size_t k = 0; k + 1 < layers[layer].size(); ++k) {
      touch(layers[layer][k], layers[layer][k + 1]);
      if (layer + 1 < layers.size()) {
        touch(layers[layer][k], layers[layer + 1][k]);
        touch(layers[layer][k + 1], layers[layer + 1][k]);
      }
    }
  }
  return p;
}

TEST(NonsmoothIslandJoint, PyramidsOfLeaningStonesObeyEveryLawWithActiveSetSteps) {
  // The active-set steps (a semismooth Newton step on the contact states the sweeps reached) must
  // leave an answer that obeys the laws wherever the solve converges: pyramids of 3 to 6 stones
  // at the base, steep and shallow, with little and much friction, at rest or with the top stone
  // sliding and spinning.
  int converged = 0, problems = 0;
  for (const int base : {3, 4, 5, 6}) {
    for (const double slope_deg : {10.0, 35.0, 60.0}) {
      for (const double mu : {0.1, 0.3, 0.6, 1.0}) {
        for (const bool moving : {false, true}) {
          SCOPED_TRACE(testing::Message() << "base " << base << ", slope " << slope_deg
                                          << " deg, mu " << mu << ", moving " << moving);
          const Vector3d velocity = moving ? Vector3d(0.01, 0.02, 0.0) : Vector3d::Zero();
          const Vector3d angular_velocity = moving ? Vector3d(0.0, 0.0, 3.0) : Vector3d::Zero();
          Problem p = pyramid(base, slope_deg * M_PI / 180, mu, velocity, angular_velocity);
          const std::vector<Vector3d> zero(p.states.size(), Vector3d::Zero());
          const double before = p.kinetic_energy(zero, zero);
          const Solved s = solve(p);
          ++problems;
          EXPECT_LE(p.kinetic_energy(s.dv, s.dw), before);
          if (s.iterations >= detail::kMaxJointIterations) continue;
          ++converged;
          const double scale_mps =
              std::max(9.81 * kStepS, velocity.norm() + kHalfWidthM * angular_velocity.norm());
          expect_laws_hold(p, s, 1e-7 * scale_mps);
        }
      }
    }
  }
  std::printf("[ pyramid ] %d of %d pyramids converged within %d sweeps\n", converged, problems,
              detail::kMaxJointIterations);
  EXPECT_GE(converged, problems * 9 / 10);
}

TEST(NonsmoothIslandJoint, WhereTheSweepsCrawlTheActiveSetStepReachesTheLaws) {
  // Six stones at the base, 35 deg, mu 0.3, the top stone sliding and spinning: the sweeps alone
  // take 909 (measured), with the steps 60, and the answer obeys every law.
  const Vector3d velocity(0.01, 0.02, 0.0), angular_velocity(0.0, 0.0, 3.0);
  const double scale_mps = velocity.norm() + kHalfWidthM * angular_velocity.norm();
  Problem stepped = pyramid(6, 35.0 * M_PI / 180, 0.3, velocity, angular_velocity);
  Problem swept = stepped;
  const std::vector<Vector3d> zero(stepped.states.size(), Vector3d::Zero());
  const double before = stepped.kinetic_energy(zero, zero);
  const Solved with_steps = solve(stepped, true);
  const Solved without = solve(swept, false);
  std::printf("[ pyramid ] 21 stones: %d sweeps with active-set steps, %d without\n",
              with_steps.iterations, without.iterations);
  EXPECT_LT(with_steps.iterations, detail::kMaxJointIterations);
  EXPECT_LT(5 * with_steps.iterations, without.iterations);
  expect_laws_hold(stepped, with_steps, 1e-7 * scale_mps);
  EXPECT_LE(stepped.kinetic_energy(with_steps.dv, with_steps.dw), before);
  // The sweeps' own answer, for comparison, obeys them too.
  expect_laws_hold(swept, without, 1e-7 * scale_mps);
}

}  // namespace
