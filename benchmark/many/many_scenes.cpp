// The many-stone scenes (a board of resting stones, two-stone collisions, a stone thrown into a
// cluster) and the measures computed from the samples.
#include <algorithm>
#include <cmath>

#include "many_method.h"
#include "virtual_go/body/motion_model.h"
#include "virtual_go/body/rigid_body.h"
#include "virtual_go/go/stone.h"

namespace vg_bench {
namespace {

StoneSpec make_spec(double width_m, const std::string& material) {
  virtual_go::StoneSpec spec;
  spec.size_number = 33;
  spec.width = width_m;
  spec.material = material;
  const virtual_go::Stone stone = virtual_go::make_stone(spec);
  StoneSpec s;
  s.half_width_m = stone.shape.half_width();
  s.half_height_m = stone.shape.half_height();
  s.mass_kg = stone.mass_properties.mass();
  s.principal_moments_body = stone.mass_properties.principal_moments_body();
  return s;
}

ManyStone make_stone_state(const StoneSpec& spec, Colour colour, const Eigen::Vector3d& x,
                           const Eigen::Quaterniond& q, const Eigen::Vector3d& v,
                           const Eigen::Vector3d& omega) {
  const virtual_go::MotionModel model(
      virtual_go::MotionModelKind::rigid_body,
      virtual_go::MassProperties(spec.mass_kg, spec.principal_moments_body));
  virtual_go::RigidBodyState st;
  st.position_world = x;
  st.orientation = q;
  st.velocity_world = v;
  ManyStone s;
  s.colour = colour;
  s.initial = virtual_go::with_angular_velocity_world(model, st, omega);
  s.omega_world = omega;
  return s;
}

ManyScene base_scene() {
  ManyScene sc;
  sc.black = black_stone();
  sc.white = white_stone();
  sc.gravity_world = virtual_go::kStandardGravity;
  return sc;  // material: the core's defaults (e* 0.5, mu 0.3, l_r 5 um, l_s 15 um)
}

// Go grid (MANY_STONES.md §1): 22.0 mm across (x), 23.7 mm along (y), centred on the board.
constexpr double kPitchX = 0.022, kPitchY = 0.0237;

// Column i, row j (0..18) of the checkerboard of colours: black where i + j is even.
Colour colour_at(int i, int j) { return (i + j) % 2 == 0 ? Colour::black : Colour::white; }

// The x of the 19 stones of row j: neighbours touch (centre distance = sum of half-widths, more
// than the 22 mm pitch), the row centred on the grid's x so every stone is within 0.5 mm of its
// point.
std::vector<double> row_x(const ManyScene& sc, int j) {
  std::vector<double> x(19, 0.0);
  auto half = [&](int i) {
    return (colour_at(i, j) == Colour::black ? sc.black : sc.white).half_width_m;
  };
  for (int i = 1; i < 19; ++i) x[i] = x[i - 1] + half(i - 1) + half(i);
  double shift = 0.0;
  for (int i = 0; i < 19; ++i) shift += x[i] - (i - 9) * kPitchX;
  shift /= 19.0;
  for (double& v : x) v -= shift;
  return x;
}

// The stone of column i, row j (its colour from the checkerboard) lying flat and still at
// (x, y), its lowest point drop_m above the board (z = 0).
ManyStone grid_stone(const ManyScene& sc, int i, int j, double x, double y, double drop_m) {
  const Colour c = colour_at(i, j);
  const StoneSpec& spec = c == Colour::black ? sc.black : sc.white;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  return make_stone_state(spec, c, Eigen::Vector3d(x, y, spec.half_height_m + drop_m),
                          Eigen::Quaterniond::Identity(), zero, zero);
}

}  // namespace

StoneSpec black_stone() { return make_spec(0.0222, "slate"); }
StoneSpec white_stone() { return make_spec(0.0219, "shell"); }

ManyScene resting_board(int n, double duration_s) {
  ManyScene sc = base_scene();
  sc.name = "rest_" + std::to_string(n);
  sc.kind = SceneKind::rest;
  sc.description = std::to_string(n) +
                   " stones set down flat at rest on the board (lowest points at z = 0), row "
                   "by row from A1, neighbours along a row touching";
  sc.duration_s = duration_s;
  sc.needs_stone_contact = false;  // they touch, but at rest nothing needs to push
  for (int k = 0; k < n; ++k) {
    const int i = k % 19, j = k / 19;
    sc.stones.push_back(grid_stone(sc, i, j, row_x(sc, j)[i], (j - 9) * kPitchY, 0.0));
  }
  return sc;
}

ManyScene two_stone_collision(Colour target, double speed_mps, double impact_parameter_m,
                              double dt_s) {
  ManyScene sc = base_scene();
  const bool head_on = impact_parameter_m == 0.0;
  sc.name =
      std::string(head_on ? "head_on" : "oblique") + "_b" + (target == Colour::black ? "b" : "w");
  sc.kind = SceneKind::collision;
  sc.description = std::string("black at ") + std::to_string(speed_mps) + " m/s into " +
                   (target == Colour::black ? "black" : "white") + " at rest";
  sc.board_enabled = false;
  sc.gravity_world = Eigen::Vector3d::Zero();
  sc.needs_stone_contact = true;
  const StoneSpec& t = target == Colour::black ? sc.black : sc.white;
  const double touch = sc.black.half_width_m + t.half_width_m;
  const double gap_x = speed_mps * 2.5 * dt_s;  // first touch between steps 2 and 3
  const double b = impact_parameter_m;
  const double x0 = -(std::sqrt(touch * touch - b * b) + gap_x);
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  const Eigen::Quaterniond flat = Eigen::Quaterniond::Identity();
  sc.stones.push_back(make_stone_state(sc.black, Colour::black, Eigen::Vector3d(x0, 0.0, 0.0), flat,
                                       Eigen::Vector3d(speed_mps, 0.0, 0.0), zero));
  sc.stones.push_back(make_stone_state(t, target, Eigen::Vector3d(0.0, b, 0.0), flat, zero, zero));
  // Long enough for both to move a stone width apart after the impact, and at least 30 steps
  // (a soft contact at a coarse step lasts several steps).
  sc.duration_s = 2.5 * dt_s + std::max(3.0 * touch / speed_mps, 30.0 * dt_s);
  return sc;
}

ManyScene thrown_into_cluster(double duration_s) {
  ManyScene sc = base_scene();
  sc.name = "cluster";
  sc.kind = SceneKind::cluster;
  sc.description =
      "a 3 x 3 block of resting stones around K10 (rows touching as on the full board); a "
      "black stone thrown from 20 mm above the board, 120 mm away, at (1.2, 0.05, 0) m/s";
  sc.duration_s = duration_s;
  sc.needs_stone_contact = true;
  const Eigen::Quaterniond flat = Eigen::Quaterniond::Identity();
  for (int j = 8; j <= 10; ++j) {
    const std::vector<double> x = row_x(sc, j);
    for (int i = 8; i <= 10; ++i)
      sc.stones.push_back(grid_stone(sc, i, j, x[i], (j - 9) * kPitchY, 0.0));
  }
  // Lands about 75 mm further on, slides and bounces into the block's left column.
  sc.stones.push_back(make_stone_state(
      sc.black, Colour::black, Eigen::Vector3d(-0.12, 0.0, sc.black.half_height_m + 0.02), flat,
      Eigen::Vector3d(1.2, 0.05, 0.0), Eigen::Vector3d(0.0, 0.0, 5.0)));
  return sc;
}

ManyScene dropped_grid(int n, double duration_s) {
  ManyScene sc = base_scene();
  sc.name = "drops_" + std::to_string(n);
  sc.kind = SceneKind::drops;
  sc.description = std::to_string(n) +
                   " stones dropped flat from 2 to 20 mm (staggered heights) onto a 19 x 19 "
                   "grid of twice the Go pitch (44 mm x 47.4 mm), so that no two touch";
  sc.duration_s = duration_s;
  sc.needs_stone_contact = false;
  const double pitch_x = 2.0 * kPitchX, pitch_y = 2.0 * kPitchY;
  sc.board.size_x_m = 19.0 * pitch_x + 0.2;
  sc.board.size_y_m = 19.0 * pitch_y + 0.2;
  for (int k = 0; k < n; ++k) {
    const int i = k % 19, j = k / 19;
    // Heights by the golden ratio's multiples: spread evenly, no two stones' events coincide.
    const double frac = std::fmod(0.6180339887498949 * (k + 1), 1.0);
    const double drop_m = 0.002 + 0.018 * frac;
    sc.stones.push_back(grid_stone(sc, i, j, (i - 9) * pitch_x, (j - 9) * pitch_y, drop_m));
  }
  return sc;
}

double stone_energy(const ManyScene& scene, std::size_t i, const ContactSample& s) {
  const StoneSpec& spec = scene.spec(i);
  const Eigen::Matrix3d r = s.orientation.normalized().toRotationMatrix();
  const Eigen::Matrix3d inertia_world =
      r * spec.principal_moments_body.asDiagonal() * r.transpose();
  return 0.5 * spec.mass_kg * s.velocity_world.squaredNorm() +
         0.5 * s.omega_world.dot(inertia_world * s.omega_world) -
         spec.mass_kg * scene.gravity_world.dot(s.position_world);
}

namespace {

// Support of the lens about its centre in body direction u (unit): a cap point when
// |u_z| >= d/R (h = R - d |u_z|), else a rim point (h = a sqrt(1 - u_z^2)).
double lens_support(const StoneSpec& s, const Eigen::Vector3d& u_body) {
  const double r = s.sphere_radius_m(), d = s.sphere_offset_m();
  const double uz = std::abs(u_body.z());
  if (uz >= d / r) return r - d * uz;
  return s.half_width_m * std::sqrt(std::max(0.0, 1.0 - uz * uz));
}

}  // namespace

double lens_overlap_m(const StoneSpec& a, const ContactSample& sa, const StoneSpec& b,
                      const ContactSample& sb) {
  const Eigen::Vector3d d = sb.position_world - sa.position_world;
  const double reach =
      std::hypot(a.half_width_m, a.half_height_m) + std::hypot(b.half_width_m, b.half_height_m);
  if (d.norm() >= reach) return reach - d.norm();  // bounding spheres apart: negative
  const Eigen::Quaterniond qa = sa.orientation.normalized(), qb = sb.orientation.normalized();
  auto depth = [&](const Eigen::Vector3d& n) {
    return lens_support(a, qa.conjugate() * n) + lens_support(b, qb.conjugate() * (-n)) - n.dot(d);
  };
  // Directions by spherical angles; a grid first (the minimum of a smooth function of the
  // direction), then a pattern search from the best grid point.
  auto dir = [](double theta, double phi) {
    return Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                           std::cos(theta));
  };
  double best = std::numeric_limits<double>::infinity(), bt = 0.0, bp = 0.0;
  const int nt = 24, np = 48;
  for (int it = 0; it <= nt; ++it) {
    for (int ip = 0; ip < np; ++ip) {
      const double t = M_PI * it / nt, p = 2.0 * M_PI * ip / np;
      const double v = depth(dir(t, p));
      if (v < best) best = v, bt = t, bp = p;
    }
  }
  for (double step = M_PI / nt; step > 1e-7; step *= 0.5) {
    bool improved = true;
    while (improved) {
      improved = false;
      for (const auto& o : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        const double t = bt + o.first * step, p = bp + o.second * step;
        const double v = depth(dir(t, p));
        if (v < best) best = v, bt = t, bp = p, improved = true;
      }
    }
  }
  return best;
}

}  // namespace vg_bench
