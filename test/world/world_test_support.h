// Shared pieces of the world tests, written from the definitions and never calling the code under
// test for a reference: the default stone and board as numbers (CONTACT facts in docs/physics.md),
// the energy from the inertia tensor, a proven lower bound of the lens's distance to the board
// and the table (separating axes evaluated with the test's own lens support mapping), Jellett's
// integral, and a runner that samples a world on a time grid and checks in every state what
// must always hold: no overlap, no energy gain, unit quaternion.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "support/convex_reference.h"
#include "support/flight_reference.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/go/stone.h"
#include "virtual_go/world/world.h"

namespace worldtest {

namespace vg = virtual_go;
using Eigen::Quaterniond;
using Eigen::Vector3d;

// Size 33 slate: a = 11 mm, c = 4.6 mm; the real board 424.2 x 454.5 x 151.5 mm, top at z = 0.
constexpr double kG = 9.80665;
constexpr double kA = 0.011, kC = 0.0046;
const double kR = (kA * kA + kC * kC) / (2 * kC), kD = kR - kC;
constexpr double kHalfX = 0.4242 / 2, kHalfY = 0.4545 / 2, kThickness = 0.1515;
const Vector3d kGravity(0, 0, -kG);

inline vg::Stone stone() { return vg::make_stone(vg::StoneSpec{}); }
inline vg::MotionModel model() {
  return vg::MotionModel(vg::MotionModelKind::rigid_body, stone().mass_properties);
}
inline double mass() { return stone().mass_properties.mass(); }

inline vg::WorldConfig config(double restitution = 0.5, double friction = 0.3,
                              double rolling_m = 5e-6, double spinning_m = 15e-6) {
  vg::WorldConfig c(vg::MotionSetup{model(), kGravity}, stone().shape);
  for (vg::ContactMaterial* m : {&c.board_material, &c.table_material}) {
    m->restitution = restitution;
    m->friction = friction;
    m->rolling_resistance_m = rolling_m;
    m->spinning_friction_m = spinning_m;
  }
  return c;
}

// A world with no stone yet: every stone comes through add_stone.
inline vg::World empty_world() {
  return vg::World(config(0.5), std::vector<vg::RigidBodyState>{}, 0.0);
}

// The field an InvalidArgument thrown by f names, "(no error)" when none is thrown.
template <typename F>
std::string field_of(F&& f) {
  try {
    f();
  } catch (const vg::InvalidArgument& e) {
    return e.field();
  }
  return "(no error)";
}

inline vg::RigidBodyState at(const Vector3d& x, const Quaterniond& q = Quaterniond::Identity(),
                             const Vector3d& v = Vector3d::Zero()) {
  vg::RigidBodyState s;
  s.position_world = x;
  s.orientation = q;
  s.velocity_world = v;
  return s;
}

// World inertia and angular velocity from the principal moments, written here.
inline Eigen::Matrix3d inertia_world(const Quaterniond& q) {
  const Vector3d moments = stone().mass_properties.principal_moments_body();
  const Eigen::Matrix3d r = q.normalized().toRotationMatrix();
  return r * moments.asDiagonal() * r.transpose();
}
inline Vector3d omega_of(const vg::RigidBodyState& s) {
  return inertia_world(s.orientation).ldlt().solve(s.angular_momentum_world);
}
inline vg::RigidBodyState with_omega(vg::RigidBodyState s, const Vector3d& omega) {
  s.angular_momentum_world = inertia_world(s.orientation) * omega;
  return s;
}
inline double energy(const vg::RigidBodyState& s) {
  return 0.5 * mass() * s.velocity_world.squaredNorm() +
         0.5 * omega_of(s).dot(s.angular_momentum_world) - mass() * kGravity.dot(s.position_world);
}

inline vgtest::LensReference lens_ref(const vg::RigidBodyState& s) {
  vgtest::LensReference l{kA, kC};
  l.x = s.position_world;
  l.b = s.orientation.normalized() * Vector3d::UnitZ();
  return l;
}

// Gap of the lens's lowest point above the plane z = h.
inline double plane_gap(const vg::RigidBodyState& s, double h) {
  return lens_ref(s).x.z() - lens_ref(s).reach(Vector3d::UnitZ()) - h;
}

// A lower bound of the lens's distance to the board box and to the table: the separating-axis
// gap n . x - reach(n) - h_box(n) is a lower bound for every unit n. The candidates are the five
// face normals and, for each edge the lens is near, the best direction perpendicular to the edge
// line (a dense scan refined by Brent's method: flight_reference.h). A value >= -eps proves the
// lens does not overlap the board or the table by more than eps (corners are not candidates: no
// test here lands on one).
inline double proven_gap(const vg::RigidBodyState& s) {
  const vgtest::LensReference lens = lens_ref(s);
  const vgtest::BoxReference box{kHalfX, kHalfY, -kThickness, 0.0};
  auto along = [&](Vector3d n) {
    n.normalize();
    return n.dot(lens.x) - lens.reach(n) - n.dot(box.support(n));
  };
  double best = -std::numeric_limits<double>::infinity();
  for (const Vector3d& n :
       {Vector3d(Vector3d::UnitZ()), Vector3d(Vector3d::UnitX()), Vector3d(-Vector3d::UnitX()),
        Vector3d(Vector3d::UnitY()), Vector3d(-Vector3d::UnitY())}) {
    best = std::max(best, along(n));
  }
  if (best < 1e-3) {
    struct Edge {
      Vector3d p, e;
      double length;
    };
    const Edge edges[] = {
        {Vector3d(kHalfX, -kHalfY, 0), Vector3d::UnitY(), 2 * kHalfY},
        {Vector3d(-kHalfX, -kHalfY, 0), Vector3d::UnitY(), 2 * kHalfY},
        {Vector3d(-kHalfX, kHalfY, 0), Vector3d::UnitX(), 2 * kHalfX},
        {Vector3d(-kHalfX, -kHalfY, 0), Vector3d::UnitX(), 2 * kHalfX},
        {Vector3d(kHalfX, kHalfY, -kThickness), Vector3d::UnitZ(), kThickness},
        {Vector3d(-kHalfX, kHalfY, -kThickness), Vector3d::UnitZ(), kThickness},
        {Vector3d(-kHalfX, -kHalfY, -kThickness), Vector3d::UnitZ(), kThickness},
        {Vector3d(kHalfX, -kHalfY, -kThickness), Vector3d::UnitZ(), kThickness},
    };
    for (const Edge& edge : edges) {
      const double along_edge = std::clamp((lens.x - edge.p).dot(edge.e), 0.0, edge.length);
      if ((lens.x - edge.p - along_edge * edge.e).norm() > kA + 1e-3) continue;
      Vector3d n;
      vgtest::line_gap_by_scan(lens, edge.p, edge.e, &n);
      best = std::max(best, along(n));
    }
  }
  const double table = lens.x.z() - lens.reach(Vector3d::UnitZ()) + kThickness;
  return std::min(best, table);
}

// Jellett's integral for the bottom cap on a horizontal plane: J = L . (R e_z - d b)
// (docs/physics.md, "Sustained contact").
inline double jellett(const vg::RigidBodyState& s) {
  const Vector3d b = s.orientation.normalized() * Vector3d::UnitZ();
  return s.angular_momentum_world.dot(kR * Vector3d::UnitZ() - kD * b);
}

struct WorldRun {
  std::vector<vg::WorldEvent> events;
  std::vector<double> times;                                          // grid times sampled
  std::vector<vg::RigidBodyState> states;                             // state at each grid time
  double worst_gap = std::numeric_limits<double>::infinity();         // over samples and events, m
  double energy_at_start = std::numeric_limits<double>::quiet_NaN();  // J
  double energy_scale = 0.0;                                          // |E| + m g a at the start, J
  double lowest_energy = std::numeric_limits<double>::infinity();     // so far, J
  // Largest energy of a state above the energy at the start, J (must be round-off).
  double worst_energy_above_start = -std::numeric_limits<double>::infinity();
  // Largest energy of a state above the lowest energy of every earlier state (samples and
  // events in time order), J. Inside a plane contact's integrator step the samples come from
  // the dense output, whose interpolation error (~1e-13 relative) is not guarded: only step ends
  // are, so a sample may lie that much above an earlier one.
  double worst_energy_rise = 0.0;
  double worst_quaternion_norm_error = 0.0;

  // No energy gain: never above the start beyond round-off, never above an earlier state
  // beyond the dense output's interpolation error.
  void expect_no_energy_gain(double interpolation = 1e-11) const {
    EXPECT_LE(worst_energy_above_start, 1e-14 * energy_scale);
    EXPECT_LE(worst_energy_rise, interpolation * energy_scale);
  }
};

// Samples `world` at t0 + k dt up to t_end, checking every sampled state and every event's
// state; continues `r` (its energies and worst values) when called again.
inline void run_into(WorldRun& r, vg::World& world, double t_end, double dt,
                     std::size_t stone = 0) {
  if (std::isnan(r.energy_at_start)) {
    r.energy_at_start = r.lowest_energy = energy(world.state(stone));
    r.energy_scale = std::abs(r.energy_at_start) + mass() * kG * kA;
  }
  auto check = [&](const vg::RigidBodyState& s) {
    r.worst_gap = std::min(r.worst_gap, proven_gap(s));
    const double e = energy(s);
    r.worst_energy_above_start = std::max(r.worst_energy_above_start, e - r.energy_at_start);
    r.worst_energy_rise = std::max(r.worst_energy_rise, e - r.lowest_energy);
    r.lowest_energy = std::min(r.lowest_energy, e);
    r.worst_quaternion_norm_error =
        std::max(r.worst_quaternion_norm_error, std::abs(s.orientation.norm() - 1.0));
  };
  const double t0 = world.time();
  for (long k = 1;; ++k) {
    const double t = t0 + static_cast<double>(k) * dt;
    if (t > t_end + 1e-12) break;
    const std::size_t before = r.events.size();
    world.advance_to(t, r.events);
    for (std::size_t i = before; i < r.events.size(); ++i) {
      if (r.events[i].stone == stone) check(r.events[i].state);
    }
    check(world.state(stone));
    r.times.push_back(t);
    r.states.push_back(world.state(stone));
  }
}

inline WorldRun run(vg::World& world, double t_end, double dt, std::size_t stone = 0) {
  WorldRun r;
  run_into(r, world, t_end, dt, stone);
  return r;
}

inline std::vector<vg::WorldEvent> of_kind(const std::vector<vg::WorldEvent>& events,
                                           vg::WorldEventKind kind) {
  std::vector<vg::WorldEvent> out;
  for (const auto& e : events) {
    if (e.kind == kind) out.push_back(e);
  }
  return out;
}

inline const vg::WorldEvent* last_of(const std::vector<vg::WorldEvent>& events,
                                     vg::WorldEventKind kind) {
  for (auto it = events.rbegin(); it != events.rend(); ++it) {
    if (it->kind == kind) return &*it;
  }
  return nullptr;
}

}  // namespace worldtest
