#include "trajectory_metrics.h"

#include <algorithm>

#include "virtual_go/geometry/rotation.h"

namespace vg_bench {

namespace {

double kinetic_energy(const ContactScenario& sc, const ContactSample& s) {
  const Eigen::Matrix3d r = s.orientation.normalized().toRotationMatrix();
  const Eigen::Matrix3d i_world = r * sc.stone.principal_moments_body.asDiagonal() * r.transpose();
  return 0.5 * sc.stone.mass_kg * s.velocity_world.squaredNorm() +
         0.5 * s.omega_world.dot(i_world * s.omega_world);
}

double tilt(const Eigen::Quaterniond& q) {
  const double bz = (q.normalized() * Eigen::Vector3d::UnitZ()).z();
  return std::acos(std::min(1.0, std::abs(bz)));
}

}  // namespace

double penetration_depth(const BoardSpec& board, const Eigen::Vector3d& p) {
  double depth = std::max(0.0, board.table_z_m() - p.z());
  const Eigen::Vector3d local = p - board.centre_world();
  const Eigen::Vector3d half = board.half_extent_m();
  const Eigen::Vector3d inside = half - local.cwiseAbs();  // > 0 on every axis: inside
  if (inside.minCoeff() > 0.0) depth = std::max(depth, inside.minCoeff());
  return depth;
}

std::vector<Flight> find_flights(const Trajectory& tr, double g) {
  const auto& s = tr.samples;
  const double dt = tr.dt_s;
  const double gdt2 = g * dt * dt;
  // Round-off of a position is ~1e-17 m here; a contact force changes the second difference
  // by far more than 1e-6 of g dt^2 (except forces below 1e-6 of the weight).
  const double tol = 1e-6 * gdt2 + 1e-14;
  std::vector<Flight> flights;
  long run_start = -1;
  auto close_run = [&](long first_interior, long last_interior) {
    Flight f;
    f.first = first_interior - 1;
    f.last = last_interior + 1;
    // Least squares of y = z + g tau^2 / 2 = a + b tau, tau = t - t_mid.
    f.t_mid = 0.5 * (f.first + f.last) * dt;
    double st = 0, sy = 0, n = 0;
    for (long k = f.first; k <= f.last; ++k) {
      const double tau = k * dt - f.t_mid;
      st += tau;
      sy += s[k].position_world.z() + 0.5 * g * tau * tau;
      n += 1;
    }
    const double tm = st / n, ym = sy / n;
    double stt = 0, sty = 0;
    for (long k = f.first; k <= f.last; ++k) {
      const double tau = k * dt - f.t_mid;
      const double y = s[k].position_world.z() + 0.5 * g * tau * tau;
      stt += (tau - tm) * (tau - tm);
      sty += (tau - tm) * (y - ym);
    }
    f.b = sty / stt;
    f.a = ym - f.b * tm;
    flights.push_back(f);
  };
  for (long k = 1; k + 1 < static_cast<long>(s.size()); ++k) {
    const Eigen::Vector3d d2 =
        s[k + 1].position_world - 2.0 * s[k].position_world + s[k - 1].position_world;
    const bool ballistic =
        std::abs(d2.z() + gdt2) <= tol && std::abs(d2.x()) <= tol && std::abs(d2.y()) <= tol;
    if (ballistic && run_start < 0) run_start = k;
    if (!ballistic && run_start >= 0) {
      close_run(run_start, k - 1);
      run_start = -1;
    }
  }
  if (run_start >= 0) close_run(run_start, static_cast<long>(s.size()) - 2);
  return flights;
}

double flight_intersection(const Flight& f1, const Flight& f2, double g) {
  // z_i(t) = A_i + B_i t - g t^2 / 2: the quadratic terms cancel.
  const double a1 = f1.a - f1.b * f1.t_mid - 0.5 * g * f1.t_mid * f1.t_mid;
  const double b1 = f1.b + g * f1.t_mid;
  const double a2 = f2.a - f2.b * f2.t_mid - 0.5 * g * f2.t_mid * f2.t_mid;
  const double b2 = f2.b + g * f2.t_mid;
  return (a2 - a1) / (b1 - b2);
}

RunMetrics measure_run(const ContactScenario& sc, const LensHull& hull, bool exact_lens,
                       const Trajectory& tr) {
  RunMetrics m;
  const auto& s = tr.samples;
  const long n = static_cast<long>(s.size());
  const double dt = tr.dt_s, g = -sc.gravity_world.z();
  const double mass = sc.stone.mass_kg, c = sc.stone.half_height_m;
  const double weight = mass * g;

  // Energy gains.
  double e_min = INFINITY, e_prev = NAN;
  const double gain_tol = weight * 1e-10;
  for (long k = 0; k < n; ++k) {
    const double e = kinetic_energy(sc, s[k]) - mass * sc.gravity_world.dot(s[k].position_world);
    if (k > 0 && e - e_prev > gain_tol) ++m.energy_gain_steps;
    e_min = std::min(e_min, e);
    m.energy_rise_max_m = std::max(m.energy_rise_max_m, (e - e_min) / weight);
    e_prev = e;
  }

  // Penetration, tilt, the last second.
  const long window = std::min(n - 1, std::lround(1.0 / dt));
  const long w0 = n - 1 - window;
  m.penetration_rest_m = 0.0;
  m.max_tilt_rad = 0.0;
  double z_lo = INFINITY, z_hi = -INFINITY;
  m.jitter_position_m = 0.0;
  m.jitter_rotation_rad = 0.0;
  for (long k = 0; k < n; ++k) {
    const Eigen::Quaterniond q = s[k].orientation.normalized();
    const Eigen::Matrix3d r = q.toRotationMatrix();
    const Eigen::Vector3d& x = s[k].position_world;
    double depth =
        exact_lens ? penetration_depth(sc.board, sc.stone.lowest_point_world(x, q)) : 0.0;
    for (const Eigen::Vector3d& v : hull.vertices_body) {
      depth = std::max(depth, penetration_depth(sc.board, x + r * v));
    }
    m.penetration_max_m = std::max(m.penetration_max_m, depth);
    m.max_tilt_rad = std::max(m.max_tilt_rad, tilt(q));
    if (k >= w0) {
      m.penetration_rest_m = std::max(m.penetration_rest_m, depth);
      m.jitter_position_m = std::max(m.jitter_position_m, (x - s[w0].position_world).norm());
      m.jitter_rotation_rad =
          std::max(m.jitter_rotation_rad, virtual_go::orientation_error(s[w0].orientation, q));
      z_lo = std::min(z_lo, x.z());
      z_hi = std::max(z_hi, x.z());
    }
  }
  m.jitter_height_m = z_hi - z_lo;

  // Settling and sleep: the last sample that still moves / is awake.
  const double settle_energy = weight * 1e-6;
  long last_moving = -1, last_awake = -1;
  for (long k = 0; k < n; ++k) {
    if (kinetic_energy(sc, s[k]) > settle_energy) last_moving = k;
    if (!tr.asleep[k]) last_awake = k;
  }
  if (last_moving < n - 1) m.settle_time_s = (last_moving + 1) * dt;
  if (last_awake < n - 1) m.sleep_time_s = (last_awake + 1) * dt;

  const ContactSample& end = s.back();
  m.final_position = end.position_world;
  m.final_tilt_rad = tilt(end.orientation);
  {
    Eigen::Vector3d low = sc.stone.lowest_point_world(end.position_world, end.orientation);
    if (!exact_lens) {
      const Eigen::Quaterniond q = end.orientation.normalized();
      low = Eigen::Vector3d::Constant(INFINITY);
      for (const Eigen::Vector3d& v : hull.vertices_body) {
        const Eigen::Vector3d p = end.position_world + q * v;
        if (p.z() < low.z()) low = p;
      }
    }
    const Eigen::Vector3d half = sc.board.half_extent_m();
    const bool over_board = std::abs(low.x()) <= half.x() && std::abs(low.y()) <= half.y();
    m.final_gap_m = low.z() - (over_board ? sc.board.top_z_m() : sc.board.table_z_m());
  }

  if (sc.drop) {
    const FlatDropReference& ref = *sc.drop;
    const double h_min = 1e-6;
    m.bounces_reference = ref.last_bounce_above(h_min);
    m.rest_reference_s = ref.rest_time_s();
    m.rest_reference_cutoff_s = ref.rest_time_with_cutoff_s(h_min);
    const std::vector<Flight> flights = find_flights(tr, g);
    // Flight 0 is the release (it starts at sample 0); flight n the n-th bounce.
    std::vector<Flight> ordered;
    if (!flights.empty() && flights.front().first == 0) ordered = flights;
    for (size_t i = 1; i < ordered.size(); ++i) {
      if (ordered[i].apex_z(g) - c >= h_min) ++m.bounces_detected;
    }
    double apex_err = 0.0, impact_err = 0.0;
    int resolvable = 0;
    for (int b = 1; b <= m.bounces_reference; ++b) {
      BounceMetrics bm;
      bm.bounce = b;
      bm.apex_reference_m = ref.apex_height_m(b);
      bm.impact_reference_s = ref.impact_time_s(b);
      const double flight_time = ref.impact_time_s(b + 1) - ref.impact_time_s(b);
      bm.resolvable = flight_time >= 3.0 * dt;
      if (b < static_cast<int>(ordered.size())) {
        bm.apex_measured_m = ordered[b].apex_z(g) - c;
        bm.impact_measured_s = flight_intersection(ordered[b - 1], ordered[b], g);
      }
      if (bm.resolvable && b <= 3) {
        ++resolvable;
        const double ae =
            std::isnan(bm.apex_measured_m)
                ? 1.0
                : std::abs(bm.apex_measured_m - bm.apex_reference_m) / bm.apex_reference_m;
        apex_err = std::max(apex_err, ae);
        const double te = std::isnan(bm.impact_measured_s)
                              ? INFINITY
                              : std::abs(bm.impact_measured_s - bm.impact_reference_s);
        impact_err = std::max(impact_err, te);
      }
      m.bounces.push_back(bm);
    }
    if (resolvable > 0) {
      m.apex_rel_error_max = apex_err;
      m.impact_error_max_s = impact_err;
    }
  }

  if (sc.slide) {
    // Slip of the contact point (the lens' lowest point) along the slide direction.
    const Eigen::Vector3d dir = sc.initial.velocity_world.normalized();
    auto slip = [&](const ContactSample& smp) {
      const Eigen::Vector3d p = sc.stone.lowest_point_world(smp.position_world, smp.orientation);
      return (smp.velocity_world + smp.omega_world.cross(p - smp.position_world)).dot(dir);
    };
    const Eigen::Vector3d x0 = s.front().position_world;
    double max_pitch = 0.0;
    for (long k = 1; k < n; ++k) {
      const double u0 = slip(s[k - 1]), u1 = slip(s[k]);
      max_pitch = std::max(max_pitch, tilt(s[k - 1].orientation));
      // Stopped when the slip falls below 1 mm/s (a soft friction law only approaches 0);
      // the instant is where the line through the last two samples reaches 0.
      if (u1 <= 1e-3) {
        const double f = u0 > u1 ? std::min(2.0, u0 / (u0 - u1)) : 1.0;
        m.slip_end_s = (k - 1 + f) * dt;
        const Eigen::Vector3d x =
            s[k - 1].position_world + f * (s[k].position_world - s[k - 1].position_world);
        m.slip_distance_m = (x - x0).dot(dir);
        m.slip_max_pitch_rad = max_pitch;
        break;
      }
    }
    m.slide_final_m = (s.back().position_world - x0).dot(dir);
  }
  return m;
}

}  // namespace vg_bench
