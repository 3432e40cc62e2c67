// The contact scenarios (size-33 slate stone on the real board) and their closed-form
// references.
#include <cmath>

#include "contact_method.h"
#include "virtual_go/body/motion_model.h"
#include "virtual_go/body/rigid_body.h"
#include "virtual_go/geometry/rotation.h"
#include "virtual_go/go/stone.h"
#include "virtual_go/geometry/tessellation.h"

namespace vg_bench {

double StoneSpec::sphere_radius_m() const {
  const double a = half_width_m, c = half_height_m;
  return (a * a + c * c) / (2.0 * c);
}

double StoneSpec::sphere_offset_m() const { return sphere_radius_m() - half_height_m; }

Eigen::Vector3d StoneSpec::lowest_point_world(const Eigen::Vector3d& centre_world,
                                              const Eigen::Quaterniond& orientation) const {
  // Support of the lens in body direction u = -R^T e_z: a cap point when |u_z| >= d/R, else
  // a rim point (the cap's normal cone ends at cos(beta) = d/R).
  const Eigen::Vector3d u = orientation.conjugate() * Eigen::Vector3d(0.0, 0.0, -1.0);
  const double r = sphere_radius_m(), d = sphere_offset_m();
  Eigen::Vector3d s_body;
  if (std::abs(u.z()) >= d / r) {
    s_body = Eigen::Vector3d(0.0, 0.0, u.z() < 0.0 ? d : -d) + r * u;
  } else {
    const double xy = std::hypot(u.x(), u.y());
    s_body = Eigen::Vector3d(half_width_m * u.x() / xy, half_width_m * u.y() / xy, 0.0);
  }
  return centre_world + orientation * s_body;
}

double FlatDropReference::fall_time_s() const { return std::sqrt(2.0 * height_m / gravity); }

double FlatDropReference::apex_height_m(int bounce) const {
  return std::pow(restitution, 2 * bounce) * height_m;
}

double FlatDropReference::impact_time_s(int impact) const {
  // t_n = t_1 (1 + 2 (e + e^2 + ... + e^(n-1))).
  const double e = restitution;
  const double sum = impact <= 1 ? 0.0 : e * (1.0 - std::pow(e, impact - 1)) / (1.0 - e);
  return fall_time_s() * (1.0 + 2.0 * sum);
}

double FlatDropReference::rest_time_s() const {
  return fall_time_s() * (1.0 + restitution) / (1.0 - restitution);
}

int FlatDropReference::last_bounce_above(double h_min_m) const {
  int n = 0;
  while (apex_height_m(n + 1) >= h_min_m) ++n;
  return n;
}

double FlatDropReference::rest_time_with_cutoff_s(double h_min_m) const {
  return impact_time_s(last_bounce_above(h_min_m) + 1);
}

double FlatDropReference::height_at(double t) const {
  const double g = gravity;
  if (t <= fall_time_s()) return height_m - 0.5 * g * t * t;
  const int last = last_bounce_above(1e-6);
  for (int n = 1; n <= last; ++n) {
    const double t0 = impact_time_s(n), t1 = impact_time_s(n + 1);
    if (t < t1) {
      const double v = std::pow(restitution, n) * std::sqrt(2.0 * g * height_m);
      const double s = t - t0;
      return v * s - 0.5 * g * s * s;
    }
  }
  return 0.0;
}

double FlatDropReference::velocity_at(double t) const {
  const double g = gravity;
  if (t <= fall_time_s()) return -g * t;
  const int last = last_bounce_above(1e-6);
  for (int n = 1; n <= last; ++n) {
    const double t0 = impact_time_s(n), t1 = impact_time_s(n + 1);
    if (t < t1) return std::pow(restitution, n) * std::sqrt(2.0 * g * height_m) - g * (t - t0);
  }
  return 0.0;
}

double SlideReference::frozen_distance_m() const {
  return speed_mps * speed_mps / (2.0 * friction * gravity);
}

double SlideReference::frozen_stop_time_s() const { return speed_mps / (friction * gravity); }

void SlideReference::integrate_free_lens(const StoneSpec& stone) {
  // The lens slides flat along +x on its bottom cap and pitches by theta about y (the axis
  // b = (sin theta, 0, cos theta)). The contact point stays on the sphere of radius R centred
  // d above the centre of mass along b, so z_G = R - d cos(theta) (no free vertical motion),
  // r = P - G = (d sin theta, 0, d cos theta - R), friction F_x = -mu N while the contact
  // point slips forward (u = v + theta_dot (d cos theta - R) > 0), and
  //   m x'' = F_x,  m z'' = N - m g,  I1 theta'' = r_z F_x - r_x N.
  // Eliminating N with z'' = d cos(theta) theta'^2 + d sin(theta) theta'' gives the system
  // below; RK4 at 1 us, the slip end located by linear interpolation of u within the step.
  // This is an independent reference: the engines and the core integrate the full 3-D
  // equations, the benchmark only compares the results.
  const double m = stone.mass_kg, i1 = stone.principal_moments_body.x();
  const double r = stone.sphere_radius_m(), d = stone.sphere_offset_m();
  const double mu = friction, g = gravity;
  struct State {
    double x, v, th, w;
  };
  auto rhs = [&](const State& s) {
    const double a = mu * (r - d * std::cos(s.th)) - d * std::sin(s.th);
    const double n =
        m * (g + d * std::cos(s.th) * s.w * s.w) / (1.0 - m * d * std::sin(s.th) * a / i1);
    return State{s.v, -mu * n / m, s.w, n * a / i1};
  };
  auto slip = [&](const State& s) { return s.v + s.w * (d * std::cos(s.th) - r); };
  auto axpy = [](const State& s, double h, const State& k) {
    return State{s.x + h * k.x, s.v + h * k.v, s.th + h * k.th, s.w + h * k.w};
  };
  State s{0.0, speed_mps, 0.0, 0.0};
  const double h = 1e-6;
  double t = 0.0, max_pitch = 0.0;
  for (long k = 0; k < 10000000; ++k) {
    const State k1 = rhs(s), k2 = rhs(axpy(s, h / 2, k1)), k3 = rhs(axpy(s, h / 2, k2)),
                k4 = rhs(axpy(s, h, k3));
    const State n{s.x + h / 6 * (k1.x + 2 * k2.x + 2 * k3.x + k4.x),
                  s.v + h / 6 * (k1.v + 2 * k2.v + 2 * k3.v + k4.v),
                  s.th + h / 6 * (k1.th + 2 * k2.th + 2 * k3.th + k4.th),
                  s.w + h / 6 * (k1.w + 2 * k2.w + 2 * k3.w + k4.w)};
    if (slip(n) <= 0.0) {
      const double f = slip(s) / (slip(s) - slip(n));
      free_slip_end_s = t + f * h;
      free_distance_m = s.x + f * (n.x - s.x);
      free_max_pitch_rad = std::max(max_pitch, std::abs(s.th + f * (n.th - s.th)));
      return;
    }
    s = n;
    t += h;
    max_pitch = std::max(max_pitch, std::abs(s.th));
  }
}

LensHull make_lens_hull(const StoneSpec& stone) {
  const virtual_go::LensShape shape(2.0 * stone.half_width_m, 2.0 * stone.half_height_m);
  const virtual_go::TriangleMesh mesh =
      virtual_go::tessellate_lens(shape, kHullSegments, kHullRings);
  return LensHull{mesh.vertices, mesh.triangles};
}

std::vector<ContactScenario> make_contact_scenarios() {
  virtual_go::StoneSpec spec;
  spec.size_number = 33;
  spec.material = "slate";
  const virtual_go::Stone stone = virtual_go::make_stone(spec);
  const virtual_go::MassProperties& mp = stone.mass_properties;
  const virtual_go::MotionModel model(virtual_go::MotionModelKind::rigid_body, mp);

  StoneSpec s33;
  s33.half_width_m = stone.shape.half_width();
  s33.half_height_m = stone.shape.half_height();
  s33.mass_kg = mp.mass();
  s33.principal_moments_body = mp.principal_moments_body();
  const double c = s33.half_height_m;
  const BoardSpec board;
  const Eigen::Vector3d gravity = virtual_go::kStandardGravity;
  const double g = -gravity.z();

  auto make = [&](const std::string& name, const std::string& what, double duration,
                  const Eigen::Vector3d& x, const Eigen::Quaterniond& q, const Eigen::Vector3d& v,
                  const Eigen::Vector3d& omega, double restitution) {
    ContactScenario sc;
    sc.name = name;
    sc.description = what;
    sc.stone = s33;
    sc.board = board;
    sc.board_material.restitution = restitution;
    sc.table_material.restitution = restitution;
    sc.gravity_world = gravity;
    virtual_go::RigidBodyState st;
    st.position_world = x;
    st.orientation = q;
    st.velocity_world = v;
    sc.initial = virtual_go::with_angular_velocity_world(model, st, omega);
    sc.initial_omega_world = omega;
    sc.duration_s = duration;
    return sc;
  };
  const Eigen::Quaterniond flat = Eigen::Quaterniond::Identity();
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  const double h0 = 0.05;

  std::vector<ContactScenario> out;
  for (const double e : {0.5, 0.8}) {
    const std::string tag = e == 0.5 ? "drop_e05" : "drop_e08";
    ContactScenario sc = make(tag,
                              "flat drop from 5 cm (lowest point 50 mm above the board centre), "
                              "restitution " +
                                  std::string(e == 0.5 ? "0.5" : "0.8") + ", mu 0.3",
                              2.0, Eigen::Vector3d(0.0, 0.0, c + h0), flat, zero, zero, e);
    sc.drop = FlatDropReference{h0, e, g};
    out.push_back(sc);
  }
  // Tilted 25 degrees, spinning 40 rad/s about its axis with a 8 rad/s wobble, thrown up and
  // sideways: it lands tilted, on a point away from its pole (off-centre), slides, rocks and
  // settles.
  {
    const Eigen::Quaterniond tilt(
        Eigen::AngleAxisd(25.0 * M_PI / 180.0, Eigen::Vector3d(1.0, 0.3, 0.0).normalized()));
    const Eigen::Vector3d axis = tilt * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d across = tilt * Eigen::Vector3d::UnitX();
    out.push_back(make("toss",
                       "tilted 25 deg, spin 40 rad/s about the axis plus 8 rad/s across it, "
                       "thrown from 60 mm at (0.3, 0.15, 0.4) m/s: lands tilted and off-centre, "
                       "slides, rocks, settles; restitution 0.5, mu 0.3",
                       6.0, Eigen::Vector3d(0.03, -0.02, 0.06), tilt,
                       Eigen::Vector3d(0.3, 0.15, 0.4), 40.0 * axis + 8.0 * across, 0.5));
  }
  {
    ContactScenario sc =
        make("slide",
             "flat on the board (lowest point at z = 0) sliding along +x at "
             "0.5 m/s, mu 0.3, restitution 0.5",
             2.0, Eigen::Vector3d(-0.1, 0.0, c), flat, Eigen::Vector3d(0.5, 0.0, 0.0), zero, 0.5);
    sc.slide = SlideReference{0.5, 0.3, g};
    sc.slide->integrate_free_lens(s33);
    out.push_back(sc);
    ContactScenario frozen = sc;
    frozen.name = "slide_frozen";
    frozen.description =
        "the slide with the stone's rotation locked (translation only): the textbook "
        "v0^2 / (2 mu g), a test of each friction law";
    frozen.duration_s = 2.0;
    frozen.rotation_frozen = true;
    out.push_back(frozen);
  }
  out.push_back(make("rest",
                     "lying flat on the board at its exact rest height (lowest point at z = 0), "
                     "at rest, for 10 s",
                     10.0, Eigen::Vector3d(0.0, 0.0, c), flat, zero, zero, 0.5));
  // Centre 2 mm beyond the board's +x edge: the bottom cap lands on the edge line 0.13 mm above
  // its pole, the stone tips off and falls 151.5 mm onto the table.
  out.push_back(make("edge",
                     "flat drop from 5 cm with the centre 2 mm beyond the board's +x edge (half "
                     "over the edge): hits the edge, tips off, lands on the table; restitution "
                     "0.5, mu 0.3",
                     4.0, Eigen::Vector3d(0.5 * board.size_x_m + 0.002, 0.0, c + h0), flat, zero,
                     zero, 0.5));
  return out;
}

}  // namespace vg_bench
