// Convergence in the sub-step h of the island scheme (nonsmooth_island.h: Moreau-Jean, e = 0,
// Coulomb; its header says "first order in h"), measured on scenes whose answer is smooth in the
// data, each against a reference written here that does not use the scheme: the Newton-Euler
// equations of the lenses held on their contacts by Lagrange multipliers, integrated by
// Boost.Odeint (LensOde below). Where the exact plane model applies too (one stone sliding on the
// board) the two agree to 1e-15 m (TheReferenceIsTheExactPlaneModel). Contact laws as the
// island's: Coulomb on the board, no rolling resistance, no spinning friction.
//   slide     one stone sliding and spinning on the board's top face (the island with one member,
//             which is the single-stone fallback NonsmoothContact, kept from handing over to the
//             plane model);
//   abreast   two stones touching rim to rim across their motion, sliding together: both pitch
//             alike about the line of centres, so the rims stay touching (gap 0) and carry no
//             load; each stone is the reference's one stone;
//   push      a sliding stone strikes a resting one touching it ahead (impulses between members
//             plastic): the central plastic impact (contact at the centres' height, normal along
//             the centre line) leaves both at v0 / 2, flat, at once; then each pitches under its
//             friction, the rims part (translated copies: gap 2 a (1 - cos theta)) and each is the
//             reference's one stone from v0 / 2;
//   stack     a stone resting tilted on another slides off it, board and stones frictionless:
//             two bodies, two sustained loaded contacts (board-lower, lower-upper).
// The error is the largest distance of a stone's centre from the reference's at T = 0.04 s, on
// the lattice (T = K h exactly: a sample between lattice points is an energy-scaled partial
// step), for h = the default (the largest the core accepts) and four halvings; the observed
// order of each halving is log2(E(2h) / E(h)).
// Measured (centre error at the default h = 2.5e-4 s; orders down to 1.56e-5 s): slide 16.0 um,
// 1.000 throughout; abreast 16.0 um, 1.000; push 19.3 um, 1.00; stack 47.8 um, 0.82-0.87
// (rising; 6.4, 6.4, 7.7 and 22.5 um at 1e-4 s; at 3e-4 s the stack's first order is 0.7998, so
// the default stops at 2.5e-4), horizontal momentum 0 to 1e-18 kg m/s. A sliding
// lens rocks (friction c below its centre tips it towards mu c / d = 7.3 degrees, at 48 rad/s), and
// the scheme's lag in that rocking dominates: the frozen slide's symplectic-Euler term mu g T h / 2
// is only 0.59 um of the 6.4 at 1e-4 s. Checked that the tests can fail: a reference with mu 1 %
// higher gives orders 0.40, 0.25, 0.14, 0.08 (from h = 4e-4 s); the stack, when the held sweeps did
// not move the held stone (the board took the whole pair impulse), 0.79 ... 0.62 and P_x 1.15e-6 kg
// m/s at every h (both stack tests fail on that code).
#include <gtest/gtest.h>

#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include "virtual_go/contact/plane_contact.h"
#include "virtual_go/world/nonsmooth_contact.h"
#include "virtual_go/world/nonsmooth_island.h"
#include "world_test_support.h"

namespace {

using namespace worldtest;

constexpr double kMu = 0.3;
constexpr double kT = 0.04;  // s: every slide here is still sliding (v0 / (mu g) >= 0.085 s)
const double kH0 = vg::NonsmoothContactOptions{}.step_s;  // the default, then halved
const std::vector<double> kSteps = {kH0, kH0 / 2, kH0 / 4, kH0 / 8, kH0 / 16};

vg::ContactMaterial material(double mu) {
  vg::ContactMaterial m;
  m.restitution = 0.5;
  m.friction = mu;
  m.rolling_resistance_m = 0.0;  // the island has neither: the same law on both sides
  m.spinning_friction_m = 0.0;
  return m;
}

// The velocity sweeps the island runs before it starts holding a stone pressed into the board
// (nonsmooth_island.h, kNonsmoothPlainSweeps).
constexpr int kPlainSweeps = vg::kNonsmoothPlainSweeps;

vg::NonsmoothContactOptions options(double h, int max_sweeps, bool joint_solve = false) {
  vg::NonsmoothContactOptions o;
  o.joint_solve = joint_solve;
  o.step_s = h;
  o.max_sweeps = max_sweeps;
  o.plane_margin_m = 1.0;  // no contact point is 1 m inside the top face: never hands over
  o.pair_impacts = false;  // impulses between members plastic (push: the plastic impact)
  return o;
}

vg::RigidBodyState flat(double x, double y, const Vector3d& v = Vector3d::Zero(),
                        double spin = 0.0) {
  return with_omega(at(Vector3d(x, y, kC), Quaterniond::Identity(), v), Vector3d(0, 0, spin));
}

// The exact plane model's state at t (top face z = 0, whole plane: the runs stay well inside).
vg::RigidBodyState plane_reference(const vg::RigidBodyState& start, double t) {
  vg::PlaneContact p(model(), vg::LensGeometry(stone().shape), kGravity, 0.0,
                     vg::PlaneRegion::whole_plane(), material(kMu), start, 0.0);
  vg::PlaneContactOutcome o;
  do {
    o = p.advance(t);
  } while (o.time_s < t && !o.finished);
  EXPECT_EQ(o.time_s, t);
  EXPECT_FALSE(o.finished);
  return o.state;
}

// An independent reference written here: the Newton-Euler equations of rigid lenses held on
// their contacts by Lagrange multipliers (an index-3 system solved at the acceleration level),
// integrated by Boost.Odeint's Dormand-Prince 5 at 1e-13. A lens's bottom cap is the sphere of
// radius R about G + d b, its top cap the one about G - d b (b its axis, d = R - c). Contacts:
//   board   bottom cap on z = 0: phi = z_G + d b_z - R; force lambda (e_z - mu u_t / |u_t|) at
//           P = G + d b - R e_z (Coulomb while sliding: u_t the slip velocity there);
//   stack   upper's bottom cap on lower's top cap (two spheres): phi = |C_u - C_l| - 2 R,
//           frictionless, force lambda n on the upper at C_l + R n, -lambda n on the lower.
// Valid while every contact point stays on its cap, every slip speed is away from zero and every
// lambda stays positive (checked: min_lambda).
struct LensOde {
  bool stack = false;        // bodies 0 (lower) and 1 (upper) touch cap on cap
  double mu = 0.0;           // board friction
  std::size_t n = 1;         // bodies
  std::size_t on_board = 1;  // the first on_board bodies touch the board
  double m = mass(), r_cap = kR, d = kD;
  Eigen::Vector3d moments = stone().mass_properties.principal_moments_body();
  // Over every right-hand side (odeint copies the system: shared).
  struct Watch {
    double min_lambda = std::numeric_limits<double>::infinity();
    double min_slip = std::numeric_limits<double>::infinity();
  };
  std::shared_ptr<Watch> watch = std::make_shared<Watch>();

  using State = std::vector<double>;  // per body: G, v, q (w x y z), L: 13
  struct Body {
    Vector3d x, v, l, w, b;
    Quaterniond q;
    Eigen::Matrix3d inertia;
  };
  Body body(const State& y, std::size_t i) const {
    const double* p = &y[13 * i];
    Body B;
    B.x = Vector3d(p[0], p[1], p[2]);
    B.v = Vector3d(p[3], p[4], p[5]);
    B.q = Quaterniond(p[6], p[7], p[8], p[9]).normalized();
    B.l = Vector3d(p[10], p[11], p[12]);
    const Eigen::Matrix3d rot = B.q.toRotationMatrix();
    B.inertia = rot * moments.asDiagonal() * rot.transpose();
    B.w = B.inertia.ldlt().solve(B.l);
    B.b = rot.col(2);
    return B;
  }
  static State pack(const std::vector<vg::RigidBodyState>& s) {
    State y;
    for (const vg::RigidBodyState& b : s) {
      const Quaterniond q = b.orientation.normalized();
      for (double v : {b.position_world.x(), b.position_world.y(), b.position_world.z(),
                       b.velocity_world.x(), b.velocity_world.y(), b.velocity_world.z(), q.w(),
                       q.x(), q.y(), q.z(), b.angular_momentum_world.x(),
                       b.angular_momentum_world.y(), b.angular_momentum_world.z()})
        y.push_back(v);
    }
    return y;
  }
  // Forces and torques (about G) per body for multipliers lam (board per body, then the stack).
  void loads(const std::vector<Body>& B, const Eigen::VectorXd& lam, std::vector<Vector3d>& f,
             std::vector<Vector3d>& tau) const {
    f.assign(n, Vector3d::Zero());
    tau.assign(n, Vector3d::Zero());
    for (std::size_t i = 0; i < on_board; ++i) {
      const Vector3d r = d * B[i].b - r_cap * Vector3d::UnitZ();
      Vector3d u = B[i].v + B[i].w.cross(r);
      u.z() = 0.0;
      if (mu > 0) watch->min_slip = std::min(watch->min_slip, u.norm());
      const Vector3d dir =
          Vector3d::UnitZ() - (mu > 0 ? Vector3d(mu * u.normalized()) : Vector3d::Zero());
      f[i] += lam[i] * dir;
      tau[i] += r.cross(lam[i] * dir);
    }
    if (stack) {
      const Vector3d cl = B[0].x - d * B[0].b, cu = B[1].x + d * B[1].b;
      const Vector3d nrm = (cu - cl).normalized(), p = cl + r_cap * nrm;
      const double ls = lam[on_board];
      f[1] += ls * nrm;
      tau[1] += (p - B[1].x).cross(ls * nrm);
      f[0] -= ls * nrm;
      tau[0] += (p - B[0].x).cross(-ls * nrm);
    }
  }
  // Second derivatives of the constraints for given accelerations.
  Eigen::VectorXd phi_dd(const std::vector<Body>& B, const std::vector<Vector3d>& a,
                         const std::vector<Vector3d>& alpha) const {
    Eigen::VectorXd out(on_board + (stack ? 1 : 0));
    auto b_dd = [&](std::size_t i) {
      return Vector3d(alpha[i].cross(B[i].b) + B[i].w.cross(B[i].w.cross(B[i].b)));
    };
    for (std::size_t i = 0; i < on_board; ++i) out[i] = a[i].z() + d * b_dd(i).z();
    if (stack) {
      const Vector3d delta = B[1].x + d * B[1].b - B[0].x + d * B[0].b;
      const Vector3d delta_d =
          B[1].v + d * B[1].w.cross(B[1].b) - B[0].v + d * B[0].w.cross(B[0].b);
      const Vector3d delta_dd = a[1] + d * b_dd(1) - a[0] + d * b_dd(0);
      const Vector3d nrm = delta.normalized();
      out[on_board] = nrm.dot(delta_dd) +
                      (delta_d.squaredNorm() - std::pow(nrm.dot(delta_d), 2)) / delta.norm();
    }
    return out;
  }
  void accelerations(const std::vector<Body>& B, const Eigen::VectorXd& lam,
                     std::vector<Vector3d>& a, std::vector<Vector3d>& alpha) const {
    std::vector<Vector3d> f, tau;
    loads(B, lam, f, tau);
    a.resize(n);
    alpha.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      a[i] = kGravity + f[i] / m;
      alpha[i] = B[i].inertia.ldlt().solve(tau[i] - B[i].w.cross(B[i].l));
    }
  }
  void operator()(const State& y, State& dy, double /*t*/) const {
    std::vector<Body> B;
    for (std::size_t i = 0; i < n; ++i) B.push_back(body(y, i));
    const int k = static_cast<int>(on_board) + (stack ? 1 : 0);
    // phi_dd is affine in the multipliers (the slip directions do not depend on them).
    std::vector<Vector3d> a, alpha;
    Eigen::VectorXd lam = Eigen::VectorXd::Zero(k);
    accelerations(B, lam, a, alpha);
    const Eigen::VectorXd free = phi_dd(B, a, alpha);
    Eigen::MatrixXd A(k, k);
    for (int j = 0; j < k; ++j) {
      lam.setZero();
      lam[j] = 1.0;
      accelerations(B, lam, a, alpha);
      A.col(j) = phi_dd(B, a, alpha) - free;
    }
    lam = A.fullPivLu().solve(-free);
    for (int j = 0; j < k; ++j) watch->min_lambda = std::min(watch->min_lambda, lam[j]);
    accelerations(B, lam, a, alpha);
    dy.assign(y.size(), 0.0);
    std::vector<Vector3d> f, tau;
    loads(B, lam, f, tau);
    for (std::size_t i = 0; i < n; ++i) {
      double* p = &dy[13 * i];
      const Quaterniond q(y[13 * i + 6], y[13 * i + 7], y[13 * i + 8], y[13 * i + 9]);
      const Quaterniond qd = Quaterniond(0, B[i].w.x(), B[i].w.y(), B[i].w.z()) * q;
      const double vals[13] = {B[i].v.x(), B[i].v.y(),   B[i].v.z(),   a[i].x(),     a[i].y(),
                               a[i].z(),   0.5 * qd.w(), 0.5 * qd.x(), 0.5 * qd.y(), 0.5 * qd.z(),
                               tau[i].x(), tau[i].y(),   tau[i].z()};
      std::copy(vals, vals + 13, p);
    }
  }
  // The states at t from `start` (at 0).
  std::vector<vg::RigidBodyState> at_time(const std::vector<vg::RigidBodyState>& start,
                                          double t) const {
    State y = pack(start);
    namespace ode = boost::numeric::odeint;
    ode::integrate_adaptive(ode::make_controlled<ode::runge_kutta_dopri5<State>>(1e-13, 1e-13),
                            *this, y, 0.0, t, 1e-5);
    std::vector<vg::RigidBodyState> out;
    for (std::size_t i = 0; i < n; ++i) {
      const Body B = body(y, i);
      out.push_back(::worldtest::at(B.x, B.q, B.v));
      out.back().angular_momentum_world = B.l;
    }
    return out;
  }
  // Constraint residuals at the states (m): the largest |phi|.
  double residual(const std::vector<vg::RigidBodyState>& s) const {
    const State y = pack(s);
    double worst = 0.0;
    for (std::size_t i = 0; i < on_board; ++i) {
      const Body B = body(y, i);
      worst = std::max(worst, std::abs(B.x.z() + d * B.b.z() - r_cap));
    }
    if (stack) {
      const Body l = body(y, 0), u = body(y, 1);
      worst = std::max(worst, std::abs((u.x + d * u.b - l.x + d * l.b).norm() - 2 * r_cap));
    }
    return worst;
  }
};

// The island's states at the lattice point nearest T (its time in *t); mu on the board and
// between the stones (impulses between members plastic).
std::vector<vg::RigidBodyState> island_at(const std::vector<vg::RigidBodyState>& start, double h,
                                          double mu, int max_sweeps, double* t, bool joint_solve) {
  const long k = std::lround(kT / h);
  *t = static_cast<double>(k) * h;  // the island's lattice(k), t0 = 0
  std::vector<vg::IslandBody> bodies;
  const vg::BoardDistance board(vg::LensGeometry(stone().shape), vg::BoardGeometry{});
  for (const vg::RigidBodyState& s : start)
    bodies.push_back(vg::IslandBody{board, vg::MotionSetup{model(), kGravity}, s});
  vg::ContactMaterial stones = material(mu);
  stones.restitution = 0.0;
  vg::NonsmoothIsland island(bodies, material(mu), material(mu), stones, 0.0,
                             options(h, max_sweeps, joint_solve));
  const vg::IslandOutcome o = island.advance(*t);
  EXPECT_EQ(o.time_s, *t);
  EXPECT_TRUE(o.left.empty());
  return o.states;
}

struct Convergence {
  std::vector<double> error_m;         // per step size, kSteps' order
  std::vector<double> order;           // per halving
  std::vector<double> momentum_error;  // sum m v_x, island - reference, kg m/s
};

using Reference = std::function<std::vector<vg::RigidBodyState>(double t)>;

Convergence measure(const char* name, const std::vector<vg::RigidBodyState>& start, double mu,
                    const Reference& reference,
                    int max_sweeps = vg::NonsmoothContactOptions{}.max_sweeps,
                    bool joint_solve = false) {
  Convergence c;
  for (const double h : kSteps) {
    double t = 0.0;
    const std::vector<vg::RigidBodyState> s = island_at(start, h, mu, max_sweeps, &t, joint_solve);
    const std::vector<vg::RigidBodyState> r = reference(t);
    double worst = 0.0, worst_axis = 0.0, worst_v = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      worst = std::max(worst, (s[i].position_world - r[i].position_world).norm());
      worst_v = std::max(worst_v, (s[i].velocity_world - r[i].velocity_world).norm());
      const Vector3d b = s[i].orientation.normalized() * Vector3d::UnitZ();
      const Vector3d br = r[i].orientation.normalized() * Vector3d::UnitZ();
      worst_axis = std::max(worst_axis, std::atan2(b.cross(br).norm(), b.dot(br)));
    }
    c.error_m.push_back(worst);
    double p_x = 0.0, p_x_ref = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      p_x += mass() * s[i].velocity_world.x();
      p_x_ref += mass() * r[i].velocity_world.x();
    }
    c.momentum_error.push_back(p_x - p_x_ref);
    char order[32] = "";
    if (c.error_m.size() > 1) {
      c.order.push_back(std::log2(c.error_m[c.error_m.size() - 2] / worst));
      std::snprintf(order, sizeof order, " (order %.3f)", c.order.back());
    }
    std::printf(
        "[ measured ] %-7s h = %.2e s: at t = %.4f s centre error %.3e m, velocity error %.3e "
        "m/s, axis error %.3e rad, momentum_x error %.2e kg m/s%s\n",
        name, h, t, worst, worst_v, worst_axis, c.momentum_error.back(), order);
  }
  return c;
}

// Every halving converges at first order or better and the order does not fall as h shrinks
// (an error floor, an inconsistency of the scheme, shows as falling orders before it shows as
// an order below 0.8), and at the default h the error is within the scale of the scheme's
// first-order term: the friction's velocity change over T, mu g T, times h, twice (the rocking's
// lag and, pushing, one sub-step's friction impulse given to the wrong member: measured 0.27
// and 0.54 of mu g T h). Frictionless (the stack): g T h, gravity's velocity change over T
// times h.
void expect_first_order(const Convergence& c, double bound_at_default_m) {
  for (std::size_t i = 0; i < c.order.size(); ++i) {
    EXPECT_GE(c.order[i], 0.8) << "halving " << i;
    if (i > 0) {
      EXPECT_GE(c.order[i], c.order[i - 1] - 0.05) << "halving " << i;
    }
  }
  ASSERT_EQ(kSteps[0], vg::NonsmoothContactOptions{}.step_s);
  EXPECT_LE(c.error_m[0], bound_at_default_m);
}
const double kSlideBoundM = 2 * kMu * kG * kT * kH0;

// One stone per entry on the board, alone (the Odeint reference, one body each).
Reference alone(const std::vector<vg::RigidBodyState>& start) {
  return [start](double t) {
    std::vector<vg::RigidBodyState> out;
    for (const vg::RigidBodyState& s : start) {
      LensOde ode;
      ode.mu = kMu;
      out.push_back(ode.at_time({s}, t).front());
      EXPECT_GT(ode.watch->min_lambda, 0.0);  // it stays on the board
      EXPECT_GT(ode.watch->min_slip, 0.01);   // and keeps sliding (the slip direction is smooth)
      EXPECT_LE(ode.residual({out.back()}), 1e-11);
    }
    return out;
  };
}

TEST(IslandConvergence, TheReferenceIsTheExactPlaneModel) {
  // Where both apply (one stone sliding on a plane), the Odeint reference written here and the
  // exact plane model agree far below the island's errors.
  const vg::RigidBodyState start = flat(-0.1, 0.05, Vector3d(0.3, 0.1, 0), 5.0);
  const vg::RigidBodyState ode = alone({start})(kT).front(), plane = plane_reference(start, kT);
  const double dx = (ode.position_world - plane.position_world).norm();
  const double dv = (ode.velocity_world - plane.velocity_world).norm();
  std::printf("[ measured ] Odeint vs the plane model at %.3f s: %.2e m, %.2e m/s\n", kT, dx, dv);
  EXPECT_LE(dx, 1e-9);
  EXPECT_LE(dv, 1e-8);
}

TEST(IslandConvergence, AStoneSlidingAndSpinningOnTheBoardConvergesAtFirstOrder) {
  // The single-stone fallback's case (NonsmoothContact is this island with one member).
  const vg::RigidBodyState start = flat(-0.1, 0.05, Vector3d(0.3, 0.1, 0), 5.0);
  expect_first_order(measure("slide", {start}, kMu, alone({start})), kSlideBoundM);
}

TEST(IslandConvergence, WithTheJointSolveASlidingSpinningStoneAndAPushConvergeAtFirstOrder) {
  // NonsmoothContactOptions::joint_solve: the same slide, and the push below. Its friction is
  // Coulomb's exact sliding impulse (opposite the slip after it); the radial clamp it had first
  // turned the friction of the rocking (anisotropic) stone by an angle that did not shrink with h:
  // the slide's velocity error stopped at 3e-5 m/s and its last order fell to 0.92.
  const int sweeps = vg::NonsmoothContactOptions{}.max_sweeps;
  const vg::RigidBodyState start = flat(-0.1, 0.05, Vector3d(0.3, 0.1, 0), 5.0);
  expect_first_order(measure("slide j", {start}, kMu, alone({start}), sweeps, true), kSlideBoundM);
  const double v0 = 0.5;
  const std::vector<vg::RigidBodyState> pushing = {flat(-0.1 - 2 * kA, 0, Vector3d(v0, 0, 0)),
                                                   flat(-0.1, 0)};
  const std::vector<vg::RigidBodyState> after = {flat(-0.1 - 2 * kA, 0, Vector3d(v0 / 2, 0, 0)),
                                                 flat(-0.1, 0, Vector3d(v0 / 2, 0, 0))};
  expect_first_order(measure("push j", pushing, kMu, alone(after), sweeps, true), kSlideBoundM);
}

TEST(IslandConvergence, TwoStonesSlidingAbreastInContactConvergeAtFirstOrder) {
  const Vector3d v(0.3, 0, 0);
  const std::vector<vg::RigidBodyState> start = {flat(-0.1, -kA, v), flat(-0.1, kA, v)};
  expect_first_order(measure("abreast", start, kMu, alone(start)), kSlideBoundM);
}

TEST(IslandConvergence, AStonePushingARestingOneConvergesAtFirstOrder) {
  const double v0 = 0.5;
  const std::vector<vg::RigidBodyState> start = {flat(-0.1 - 2 * kA, 0, Vector3d(v0, 0, 0)),
                                                 flat(-0.1, 0)};
  const std::vector<vg::RigidBodyState> after = {flat(-0.1 - 2 * kA, 0, Vector3d(v0 / 2, 0, 0)),
                                                 flat(-0.1, 0, Vector3d(v0 / 2, 0, 0))};
  expect_first_order(measure("push", start, kMu, alone(after)), kSlideBoundM);
}

TEST(IslandConvergence, AStoneSlidingOffAnotherConvergesAtFirstOrder) {
  // The upper stone's pole on the lower's top cap beta off its axis, the upper's axis along the
  // contact normal, both at rest; board and stones frictionless. The upper slides down the
  // lower's cap, the lower slides back and rocks (horizontal momentum stays 0); the contacts
  // persist (both multipliers positive) over T.
  const double beta = 0.15;
  const Vector3d normal(std::sin(beta), 0, std::cos(beta));
  const vg::RigidBodyState lower = flat(0.02, 0.03);
  const Vector3d cap_centre = lower.position_world - kD * Vector3d::UnitZ();
  const Vector3d upper_x = cap_centre + 2 * kR * normal - kD * normal;
  const vg::RigidBodyState upper =
      at(upper_x, Quaterniond::FromTwoVectors(Vector3d::UnitZ(), normal), Vector3d::Zero());
  const std::vector<vg::RigidBodyState> start = {lower, upper};
  LensOde ode;
  ode.stack = true;
  ode.n = 2;
  const std::vector<vg::RigidBodyState> end = ode.at_time(start, kT);
  double p_x = 0.0, e0 = 0.0, e1 = 0.0;
  for (int i = 0; i < 2; ++i) {
    p_x += mass() * end[i].velocity_world.x();
    e0 += energy(start[i]);
    e1 += energy(end[i]);
  }
  std::printf(
      "[ measured ] stack reference at %.3f s: smallest multiplier %.3e N, constraint residual "
      "%.1e m, momentum_x %.1e kg m/s, energy change %.1e J; the upper moved %.3f mm\n",
      kT, ode.watch->min_lambda, ode.residual(end), p_x, e1 - e0,
      1e3 * (end[1].position_world - upper.position_world).norm());
  ASSERT_GT(ode.watch->min_lambda, 0.0);
  ASSERT_LE(ode.residual(end), 1e-11);
  ASSERT_LE(std::abs(e1 - e0), 1e-12);
  const Reference reference = [&](double t) {
    LensOde o;
    o.stack = true;
    o.n = 2;
    return o.at_time(start, t);
  };
  // The island's default sweeps (the held ones included: a stone pressed into the board holds
  // while the board carries its part of the pair impulse). Horizontal momentum stays the
  // reference's (0: the board is frictionless) to round-off at every h.
  const Convergence c = measure("stack", start, 0.0, reference);
  expect_first_order(c, kG * kT * kH0);
  for (const double p : c.momentum_error) EXPECT_LE(std::abs(p), 1e-15);
}

TEST(IslandConvergence, AFrictionlessBoardKeepsTheHorizontalMomentumOfAStack) {
  // Only the board acts from outside, and frictionless it pushes along its normal (z): the
  // horizontal momentum of the stones, sum m v_xy computed here from the handed-out states,
  // stays 0 at every lattice point, the held sweeps included (they act from sub-step 1: the
  // upper stone presses the lower into the board). The upper stone leans on the lower's cap off
  // its axis in x and y (no symmetry to keep it). Before the fix the held sweeps gave the upper
  // stone the rest of the pair impulse alone: 1.15e-6 kg m/s at 40 ms, at every h.
  const Vector3d normal = Vector3d(0.12, -0.09, 1.0).normalized();
  const vg::RigidBodyState lower = flat(0.02, 0.03);
  const Vector3d cap_centre = lower.position_world - kD * Vector3d::UnitZ();
  const vg::RigidBodyState upper =
      at(cap_centre + 2 * kR * normal - kD * normal,
         Quaterniond::FromTwoVectors(Vector3d::UnitZ(), normal), Vector3d::Zero());
  for (const double h : {kH0, kH0 / 4}) {
    const vg::BoardDistance board(vg::LensGeometry(stone().shape), vg::BoardGeometry{});
    std::vector<vg::IslandBody> bodies;
    for (const vg::RigidBodyState& s : {lower, upper})
      bodies.push_back(vg::IslandBody{board, vg::MotionSetup{model(), kGravity}, s});
    vg::ContactMaterial stones = material(0.0);
    stones.restitution = 0.0;
    vg::NonsmoothContactOptions o;  // the defaults but h
    o.step_s = h;
    vg::NonsmoothIsland island(bodies, material(0.0), material(0.0), stones, 0.0, o);
    double worst = 0.0, p_z_low = 0.0;
    for (int k = 1; k <= 40; ++k) {
      const vg::IslandOutcome out = island.advance(k * 1e-3);
      ASSERT_TRUE(out.left.empty());
      Vector3d p = Vector3d::Zero();
      for (const vg::RigidBodyState& s : out.states) p += mass() * s.velocity_world;
      worst = std::max(worst, std::hypot(p.x(), p.y()));
      p_z_low = std::min(p_z_low, p.z());
    }
    const vg::NonsmoothCounters& n = island.counters();
    std::printf(
        "[ measured ] stack on a frictionless board, h = %.1e s: largest |P_xy| %.2e kg m/s over "
        "40 ms (scale 2 m g T = %.2e), %ld sub-steps, %ld velocity sweeps (most %d), %ld pair "
        "impulses\n",
        h, worst, 2 * mass() * kG * 0.04, n.steps, n.velocity_sweeps, n.most_velocity_sweeps,
        n.pair_impulses);
    EXPECT_GT(n.most_velocity_sweeps, kPlainSweeps);  // the held sweeps did act
    EXPECT_LE(worst, 1e-16);
    EXPECT_LT(p_z_low, 0.0);  // the upper stone does come down (the scene is not static)
  }
}

}  // namespace
