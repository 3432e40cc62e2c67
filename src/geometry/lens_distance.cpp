#include "virtual_go/geometry/lens_distance.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <limits>
#include <vector>

namespace virtual_go {

namespace {

// A unit vector perpendicular to the unit vector e.
Eigen::Vector3d any_perpendicular(const Eigen::Vector3d& e) {
  const Eigen::Vector3d a =
      std::abs(e.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (a - a.dot(e) * e).normalized();
}

bool cap_faces(const LensGeometry& lens, int sigma, double ct) {
  return sigma > 0 ? ct >= lens.cos_cap_cone() : ct <= -lens.cos_cap_cone();
}

LensPart cap_part(int sigma) { return sigma > 0 ? LensPart::bottom_cap : LensPart::top_cap; }

}  // namespace

LensPose lens_pose(const RigidBodyState& state) {
  LensPose pose;
  pose.center_world = state.position_world;
  pose.axis_world = state.orientation * Eigen::Vector3d::UnitZ();
  return pose;
}

Eigen::Vector3d lens_support_world(const LensGeometry& lens, const LensPose& pose,
                                   const Eigen::Vector3d& n, LensPart* part) {
  const Eigen::Vector3d& x = pose.center_world;
  const Eigen::Vector3d& b = pose.axis_world;
  const double ct = b.dot(n);
  const LensPart p = lens.part_towards_plane(ct);
  if (part) *part = p;
  const double d = lens.sphere_offset(), r = lens.sphere_radius();
  switch (p) {
    case LensPart::bottom_cap:  // sphere centre x + d b
      return x + d * b - r * n;
    case LensPart::top_cap:  // sphere centre x - d b
      return x - d * b - r * n;
    case LensPart::rim:
    default: {
      // The rim point whose radial direction is -n projected onto the rim plane; |v| > 0
      // because |ct| < d/R < 1 on the rim.
      const Eigen::Vector3d v = ct * b - n;
      return x + (lens.half_width() / v.norm()) * v;
    }
  }
}

double lens_gap_value_along(const LensGeometry& lens, const LensPose& pose,
                            const Eigen::Vector3d& n, double support_m) {
  return n.dot(pose.center_world) - lens.reach(pose.axis_world.dot(n)) - support_m;
}

LensContact lens_gap_along(const LensGeometry& lens, const LensPose& pose, const Eigen::Vector3d& n,
                           double support_m) {
  LensContact c;
  c.normal_world = n;
  c.gap_m = lens_gap_value_along(lens, pose, n, support_m);
  c.point_world = lens_support_world(lens, pose, n, &c.part);
  return c;
}

LensContact lens_point_distance(const LensGeometry& lens, const LensPose& pose,
                                const Eigen::Vector3d& p) {
  const Eigen::Vector3d& x = pose.center_world;
  const Eigen::Vector3d& b = pose.axis_world;
  const double d = lens.sphere_offset(), r = lens.sphere_radius();
  // The two spheres whose intersection is the lens: sigma = +1 carries the bottom cap.
  std::array<Eigen::Vector3d, 2> delta;  // sphere centre - p
  std::array<double, 2> dist, gap;
  for (int k = 0; k < 2; ++k) {
    const int sigma = k == 0 ? 1 : -1;
    delta[k] = x + (sigma * d) * b - p;
    dist[k] = delta[k].norm();
    gap[k] = dist[k] - r;
  }
  LensContact c;
  if (gap[0] <= 0.0 && gap[1] <= 0.0) {
    // Inside both balls, i.e. inside the lens: the lens boundary is on the two spheres, so the
    // nearest boundary point is on the nearer sphere, R - |p - S| away.
    const int k = gap[0] >= gap[1] ? 0 : 1;
    const int sigma = k == 0 ? 1 : -1;
    c.gap_m = gap[k];
    c.normal_world = dist[k] > 0.0 ? Eigen::Vector3d(delta[k] / dist[k])
                                   : Eigen::Vector3d(sigma * b);  // p at a sphere centre
    c.point_world = x + (sigma * d) * b - r * c.normal_world;
    c.part = cap_part(sigma);
    return c;
  }
  // Outside: the nearest rim point is a lens point, so its distance is an upper bound; a cap
  // whose sphere's nearest point lies on the cap gives the exact distance; when neither cap
  // does, the nearest lens point is on the rim.
  Eigen::Vector3d radial = (p - x) - (p - x).dot(b) * b;
  const double radial_norm = radial.norm();
  radial = radial_norm > 0.0 ? Eigen::Vector3d(radial / radial_norm) : any_perpendicular(b);
  const Eigen::Vector3d rim_point = x + lens.half_width() * radial;
  const Eigen::Vector3d to_rim = rim_point - p;
  const double rim_dist = to_rim.norm();
  c.gap_m = rim_dist;
  c.point_world = rim_point;
  c.normal_world = rim_dist > 0.0 ? Eigen::Vector3d(to_rim / rim_dist) : Eigen::Vector3d(-radial);
  c.part = LensPart::rim;
  for (int k = 0; k < 2; ++k) {
    const int sigma = k == 0 ? 1 : -1;
    if (!(gap[k] > 0.0)) continue;
    const Eigen::Vector3d n = delta[k] / dist[k];
    if (cap_faces(lens, sigma, b.dot(n)) && gap[k] <= c.gap_m) {
      c.gap_m = gap[k];
      c.normal_world = n;
      c.point_world = x + (sigma * d) * b - r * n;
      c.part = cap_part(sigma);
    }
  }
  return c;
}

LensContact lens_line_distance(const LensGeometry& lens, const LensPose& pose,
                               const Eigen::Vector3d& p0, const Eigen::Vector3d& direction) {
  const Eigen::Vector3d e = direction.normalized();
  const Eigen::Vector3d& x = pose.center_world;
  const Eigen::Vector3d& b = pose.axis_world;
  const double d = lens.sphere_offset(), r = lens.sphere_radius();
  const Eigen::Vector3d w = x - p0;
  const Eigen::Vector3d w_perp = w - w.dot(e) * e;
  const Eigen::Vector3d b_perp = b - b.dot(e) * e;

  // Closed form: a cap whose sphere's nearest point to the line lies on the cap.
  for (int sigma : {1, -1}) {
    const Eigen::Vector3d s_perp = w_perp + (sigma * d) * b_perp;
    const double len = s_perp.norm();
    if (len >= r && len > 0.0) {
      const Eigen::Vector3d n = s_perp / len;
      if (cap_faces(lens, sigma, b.dot(n))) {
        LensContact c;
        c.gap_m = len - r;
        c.normal_world = n;
        c.point_world = x + (sigma * d) * b - r * n;
        c.part = cap_part(sigma);
        return c;
      }
    }
  }

  // General case: maximise F(psi) = n . w - reach(b . n) over the unit directions
  // n(psi) = cos psi u1 + sin psi u2 perpendicular to the line. F is the separating-axis gap;
  // when apart its only local maximum with F > 0 is the global one (the gap is concave and
  // positively homogeneous in n), so the sampled local maxima are refined and the best kept.
  // Sampling finds every basin: the lens's reach varies on the scale of the cap/rim angles
  // (tenths of a radian), far wider than the sample spacing.
  const double w_len = w_perp.norm();
  const Eigen::Vector3d u1 = w_len > 0.0 ? Eigen::Vector3d(w_perp / w_len) : any_perpendicular(e);
  const Eigen::Vector3d u2 = e.cross(u1);
  const double b1 = b.dot(u1), b2 = b.dot(u2);
  auto f = [&](double psi) {
    return w_len * std::cos(psi) - lens.reach(b1 * std::cos(psi) + b2 * std::sin(psi));
  };
  auto df = [&](double psi) {
    const double c = std::cos(psi), s = std::sin(psi);
    return -w_len * s - lens.reach_slope(b1 * c + b2 * s) * (-b1 * s + b2 * c);
  };
  constexpr int kSamples = 32;
  const double h = 2.0 * M_PI / kSamples;
  std::array<double, kSamples> values;
  for (int j = 0; j < kSamples; ++j) values[j] = f(j * h);
  std::vector<int> peaks;
  for (int j = 0; j < kSamples; ++j) {
    const double prev = values[(j + kSamples - 1) % kSamples], next = values[(j + 1) % kSamples];
    if (values[j] >= prev && values[j] > next) peaks.push_back(j);
  }
  if (peaks.empty()) {  // a constant F (line along the axis through G): any direction
    peaks.push_back(0);
  }
  std::sort(peaks.begin(), peaks.end(), [&](int i, int j) { return values[i] > values[j]; });
  if (peaks.size() > 4) peaks.resize(4);
  double best_psi = 0.0, best_value = -std::numeric_limits<double>::infinity();
  for (int j : peaks) {
    const double lo = (j - 1) * h, hi = (j + 1) * h;
    const double dlo = df(lo), dhi = df(hi);
    double psi;
    if (dlo > 0.0 && dhi < 0.0) {
      // F' is continuous (the reach is C1), so its sign change brackets the maximum.
      std::uintmax_t iterations = 60;
      const auto bracket = boost::math::tools::toms748_solve(
          df, lo, hi, dlo, dhi,
          boost::math::tools::eps_tolerance<double>(std::numeric_limits<double>::digits - 1),
          iterations);
      psi = 0.5 * (bracket.first + bracket.second);
    } else {
      // No clean sign change (a maximum at a sample, or overlapping): Brent's minimiser.
      psi = boost::math::tools::brent_find_minima([&](double t) { return -f(t); }, lo, hi,
                                                  std::numeric_limits<double>::digits / 2)
                .first;
    }
    const double value = f(psi);
    if (value > best_value) {
      best_value = value;
      best_psi = psi;
    }
  }
  const Eigen::Vector3d n = std::cos(best_psi) * u1 + std::sin(best_psi) * u2;
  return lens_gap_along(lens, pose, n, n.dot(p0));
}

Eigen::Vector3d lens_point_carried(const Eigen::Vector3d& point_world, const LensPose& from,
                                   const LensPose& to) {
  const Eigen::Vector3d r = point_world - from.center_world;
  const Eigen::Vector3d w = from.axis_world.cross(to.axis_world);
  const double c = from.axis_world.dot(to.axis_world);
  if (!(c > -0.5)) {
    return to.center_world + Eigen::Quaterniond::FromTwoVectors(from.axis_world, to.axis_world) * r;
  }
  // R = 1 + [w] + [w]^2 / (1 + c): the rotation about w by the angle between the axes.
  const Eigen::Vector3d wr = w.cross(r);
  return to.center_world + r + wr + w.cross(wr) / (1.0 + c);
}

}  // namespace virtual_go
