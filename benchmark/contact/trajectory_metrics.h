// What the contact benchmark measures in one run (a method, a scenario, a step size), computed
// from the states the method reported on the grid t_k = k dt.
#pragma once

#include <cmath>
#include <vector>

#include "contact_method.h"

namespace vg_bench {

struct Trajectory {
  double dt_s = 0.0;
  std::vector<ContactSample> samples;  // k = 0 .. N
  std::vector<char> asleep;            // the method's own sleeping flag at t_k
};

// A run of samples on one free-flight parabola z(t) = A + B t - g t^2 / 2 (found from the
// positions alone, so it works for every method and integrator alike).
struct Flight {
  long first = 0, last = 0;  // sample indices, last - first >= 2
  double a = 0.0, b = 0.0;   // z(t) = a + b (t - t_mid) - g (t - t_mid)^2 / 2
  double t_mid = 0.0;
  double apex_z(double g) const { return a + b * b / (2.0 * g); }
  double apex_time(double g) const { return t_mid + b / g; }
};

// Samples k-1, k, k+1 lie on one parabola of gravity g (second differences of x, y and z).
std::vector<Flight> find_flights(const Trajectory& tr, double g);
// The instant where two flights' parabolas meet (the impact of a rigid bounce between them).
double flight_intersection(const Flight& before, const Flight& after, double g);

struct BounceMetrics {
  int bounce = 0;                   // n >= 1
  double apex_reference_m = NAN;    // e^(2n) h0
  double apex_measured_m = NAN;     // of the centre, minus c
  double impact_reference_s = NAN;  // impact n, before bounce n
  double impact_measured_s = NAN;
  bool resolvable = false;  // the reference flight spans >= 3 dt (enough samples for a fit)
};

struct RunMetrics {
  // Flat drop
  std::vector<BounceMetrics> bounces;    // n = 1 .. the reference count above 1 um
  int bounces_reference = 0;             // bounces higher than 1 um (closed form)
  int bounces_detected = 0;              // flights after the first, with apex >= 1 um
  double apex_rel_error_max = NAN;       // over resolvable bounces 1..3 (missing = 1)
  double impact_error_max_s = NAN;       // over resolvable impacts 1..3
  double rest_reference_s = NAN;         // closed form, Zeno limit
  double rest_reference_cutoff_s = NAN;  // with the 1 um cut-off
  // Energy E = m v^2 / 2 + w.I w / 2 + m g z; gains as heights E / (m g)
  long energy_gain_steps = 0;      // steps where E rose by more than 0.1 nm of height
  double energy_rise_max_m = 0.0;  // largest rise of E above its running minimum
  // Penetration of the hull's vertices and the lens' lowest point into the board or table
  double penetration_max_m = 0.0;   // over the run
  double penetration_rest_m = NAN;  // over the last second
  // The last second of the run
  double jitter_position_m = NAN;  // largest displacement from the window's first pose
  double jitter_rotation_rad = NAN;
  double jitter_height_m = NAN;  // max z - min z of the centre
  double settle_time_s = NAN;    // kinetic energy below m g 1 um for good; NaN: never
  double sleep_time_s = NAN;     // asleep for good; NaN: never slept
  // Final pose
  Eigen::Vector3d final_position = Eigen::Vector3d::Constant(NAN);
  double final_tilt_rad = NAN;  // symmetry axis from the vertical
  double final_gap_m = NAN;     // lowest point above the surface under it (< 0: sunk)
  double max_tilt_rad = NAN;    // over the run
  // Slide
  double slip_end_s = NAN;       // contact point slip speed reaches 0
  double slip_distance_m = NAN;  // centre displacement along the slide at slip end
  double slide_final_m = NAN;    // centre displacement along the slide at the end
  double slip_max_pitch_rad = NAN;
};

// Penetration and the final gap are measured on the geometry the method collides: the hull's
// vertices for the peers (they lie on the lens, so a polyhedron resting on a facet is not
// counted as sunk), the exact lens (its lowest point, and the vertices) for ours.
RunMetrics measure_run(const ContactScenario& sc, const LensHull& hull, bool exact_lens,
                       const Trajectory& tr);

// Penetration depth (m, >= 0) of a world point into the board box or below the table plane.
double penetration_depth(const BoardSpec& board, const Eigen::Vector3d& p_world);

}  // namespace vg_bench
