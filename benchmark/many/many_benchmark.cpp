// The many-stone benchmark: ours (virtual_go::World) against Bullet, ODE and MuJoCo, each set
// up as the contact benchmark's "tuned" variant (as each engine's documentation says for small
// bodies) with sleeping on where the engine has it. Three sections:
//   rest      N = 1, 10, 100, 361 stones resting on the board for 10 s at dt = 1/60 s: cost
//             per step, and whether the stones creep or jitter (displacement, speed, sleep)
//   collision two stones free in the air, head-on and oblique, at several speeds and steps:
//             momentum error and energy change per collision (peers; ours: not yet)
//   cluster   a stone thrown into a 3 x 3 block: energy history, overlap, time to sleep
//   drops     ours only: N = 1, 10, 100, 361 stones dropped apart, each bouncing to rest: cost
//             per event and per advance_to as N grows (issue 15: at most log N per event)
// Writes into --out DIR: many_results.csv (every figure, long format), many_tables.md,
// many_settings.md, many_cost.dat (for the plot). scripts/benchmark.sh --many-only runs it and
// writes docs/benchmarks/many.md.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "../contact/settings_format.h"
#include "../output_folder.h"
#include "many_method.h"
#include "virtual_go/world/nonsmooth_island.h"

namespace vg_bench {
namespace {

using Clock = std::chrono::steady_clock;

struct Options {
  bool quick = false;
  std::string methods = "ours,bullet,ode,mujoco";  // which to run, comma-separated
  std::vector<int> counts = {1, 10, 100, 361};     // resting-board sizes
  std::string out = ".";
  double nonsmooth_step_s = 0.0;  // > 0: ours' island sub-step h (default otherwise)
  bool joint_solve = false;       // ours with NonsmoothContactOptions::joint_solve
  bool hold_check = true;         // ours with NonsmoothContactOptions::hold_check
};

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string dt_text(double dt) {
  const double inv = 1.0 / dt;
  return "1/" + std::to_string(static_cast<long>(std::lround(inv)));
}

// Durations in ns, us or ms with three significant digits.
std::string time_text(double ns) {
  if (std::isnan(ns)) return "-";
  char b[64];
  if (ns < 1e3)
    std::snprintf(b, sizeof b, "%.3g ns", ns);
  else if (ns < 1e6)
    std::snprintf(b, sizeof b, "%.3g us", ns / 1e3);
  else
    std::snprintf(b, sizeof b, "%.3g ms", ns / 1e6);
  return b;
}

std::string sci(double v) {
  if (std::isnan(v)) return "-";
  char b[64];
  std::snprintf(b, sizeof b, "%.2e", v);
  return b;
}

class Csv {
 public:
  explicit Csv(const std::string& path) : f_(path) {
    f_ << "section,scene,method,dt_s,stones,metric,value\n";
  }
  void put(const std::string& section, const std::string& scene, const std::string& method,
           double dt, std::size_t n, const std::string& metric, double value) {
    f_ << section << "," << scene << "," << method << "," << num17(dt) << "," << n << "," << metric
       << "," << num17(value) << "\n";
  }
  void note(const std::string& section, const std::string& scene, const std::string& method,
            double dt, std::size_t n, const std::string& metric, const std::string& text) {
    f_ << section << "," << scene << "," << method << "," << num17(dt) << "," << n << "," << metric
       << ",\"" << text << "\"\n";
  }

 private:
  std::ofstream f_;
};

long steps_of(const ManyScene& s, double dt) { return std::lround(s.duration_s / dt); }

// ---- rest --------------------------------------------------------------------------------

struct RestRun {
  std::string not_run;  // non-empty: refused, with the reason
  std::string failure;
  double cost_ns = NAN;       // per step over the whole run, median of the repetitions
  double cost_last_ns = NAN;  // per step over the last second, median of the repetitions
  int reps = 0;
  double max_horizontal_m = 0.0, max_vertical_m = 0.0;  // of any stone from its start
  double max_rotation_rad = 0.0;
  double max_speed_mps = 0.0, max_speed_last_mps = 0.0;  // any stone; the last second
  std::size_t asleep_end = 0;
  double all_asleep_s = NAN;   // first grid time at which every stone was asleep
  double last_moving_s = NAN;  // last grid time at which some stone moved faster than 1 mm/s
  long work = -1;              // ours: integration work over the run
};

// Timed repetitions of the whole run (reset untimed): cost per step over all steps and over
// the last second, medians of the repetitions.
void time_runs(ManyMethod& m, const ManyScene& s, double dt, double budget_s, int min_reps,
               int max_reps, std::vector<double> all, std::vector<double> tail, double& cost_ns,
               double& cost_last_ns, int& reps) {
  const long steps = steps_of(s, dt);
  const long last = std::min(steps, std::lround(1.0 / dt));
  double spent = 0.0;
  for (double a : all) spent += a * steps * 1e-9;
  while ((static_cast<int>(all.size()) < min_reps || spent < budget_s) &&
         static_cast<int>(all.size()) < max_reps) {
    m.reset(s, dt);
    const auto t0 = Clock::now();
    for (long k = 0; k < steps - last; ++k) m.advance();
    const auto t1 = Clock::now();
    for (long k = steps - last; k < steps; ++k) m.advance();
    const auto t2 = Clock::now();
    const double total = std::chrono::duration<double, std::nano>(t2 - t0).count();
    all.push_back(total / steps);
    tail.push_back(std::chrono::duration<double, std::nano>(t2 - t1).count() / last);
    spent += total * 1e-9;
  }
  cost_ns = median(all);
  cost_last_ns = median(tail);
  reps = static_cast<int>(all.size());
}

RestRun run_rest(ManyMethod& m, const ManyScene& s, double dt, const Options& o) {
  RestRun r;
  try {
    m.reset(s, dt);
  } catch (const ContactNotRun& e) {
    r.not_run = e.what();
    return r;
  }
  const std::size_t n = s.stones.size();
  std::vector<ContactSample> start(n);
  for (std::size_t i = 0; i < n; ++i) start[i] = m.sample(i);
  const long steps = steps_of(s, dt);
  const long last_from = steps - std::lround(1.0 / dt);
  // The measurement pass is also the first timed repetition (the sampling is not timed).
  double pass_ns = 0.0, pass_last_ns = 0.0;
  for (long k = 1; k <= steps; ++k) {
    const auto c0 = Clock::now();
    m.advance();
    const double step_ns = std::chrono::duration<double, std::nano>(Clock::now() - c0).count();
    pass_ns += step_ns;
    if (k > last_from) pass_last_ns += step_ns;
    const double t = k * dt;
    bool all_asleep = true, moving = false;
    for (std::size_t i = 0; i < n; ++i) {
      const ContactSample p = m.sample(i);
      const Eigen::Vector3d d = p.position_world - start[i].position_world;
      r.max_horizontal_m = std::max(r.max_horizontal_m, std::hypot(d.x(), d.y()));
      r.max_vertical_m = std::max(r.max_vertical_m, std::abs(d.z()));
      r.max_rotation_rad =
          std::max(r.max_rotation_rad, p.orientation.angularDistance(start[i].orientation));
      // A point on the rim moves at most |v| + a |w|.
      const double speed = p.velocity_world.norm() + s.spec(i).half_width_m * p.omega_world.norm();
      r.max_speed_mps = std::max(r.max_speed_mps, speed);
      if (k > last_from) r.max_speed_last_mps = std::max(r.max_speed_last_mps, speed);
      if (speed > 1e-3) moving = true;
      if (!m.asleep(i)) all_asleep = false;
    }
    if (all_asleep && std::isnan(r.all_asleep_s)) r.all_asleep_s = t;
    if (moving) r.last_moving_s = t;
  }
  for (std::size_t i = 0; i < n; ++i) r.asleep_end += m.asleep(i) ? 1 : 0;
  r.failure = m.failure();
  r.work = m.work_done();
  const bool ours = !m.is_peer();
  // Ours costs nanoseconds per call: many repetitions of the run for a stable median.
  // Peers: further repetitions while the budget lasts (the full board at 1/60 s may get
  // only the measurement pass). Ours: the measurement pass is not used (its clock reads per
  // step would dominate), many repetitions of the bare loop instead.
  std::vector<double> all, tail;
  if (!ours) {
    all.push_back(pass_ns / steps);
    tail.push_back(pass_last_ns / (steps - last_from));
  }
  time_runs(m, s, dt, o.quick ? (ours ? 0.05 : 0.0) : (ours ? 0.3 : 4.0), ours ? 3 : 1,
            ours ? 2000 : (o.quick ? 1 : 5), all, tail, r.cost_ns, r.cost_last_ns, r.reps);
  return r;
}

// ---- collisions --------------------------------------------------------------------------

struct CollisionRun {
  std::string not_run, failure;
  double momentum_error = NAN;      // |p1 - p0| / |p0|
  double energy_change = NAN;       // (E1 - E0) / E0
  double energy_expected = NAN;     // head-on: -(1 - e^2) m_B / (m_A + m_B)
  double target_speed_error = NAN;  // head-on: v_B' against (1 + e) m_A / (m_A + m_B) v
  double max_overlap_m = NAN;
  bool hit = false;
};

CollisionRun run_collision(ManyMethod& m, const ManyScene& s, double dt, double b, double speed) {
  CollisionRun r;
  try {
    m.reset(s, dt);
  } catch (const ContactNotRun& e) {
    r.not_run = e.what();
    return r;
  }
  auto momentum = [&]() {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < 2; ++i) p += s.spec(i).mass_kg * m.sample(i).velocity_world;
    return p;
  };
  auto energy = [&]() { return stone_energy(s, 0, m.sample(0)) + stone_energy(s, 1, m.sample(1)); };
  const Eigen::Vector3d p0 = momentum();
  const double e0 = energy();
  r.max_overlap_m = -1.0;
  const long steps = steps_of(s, dt);
  for (long k = 0; k < steps; ++k) {
    m.advance();
    r.max_overlap_m =
        std::max(r.max_overlap_m, lens_overlap_m(s.spec(0), m.sample(0), s.spec(1), m.sample(1)));
  }
  r.max_overlap_m = std::max(r.max_overlap_m, 0.0);
  r.momentum_error = (momentum() - p0).norm() / p0.norm();
  r.energy_change = (energy() - e0) / e0;
  const double ma = s.spec(0).mass_kg, mb = s.spec(1).mass_kg, e = s.material.restitution;
  const double vb = m.sample(1).velocity_world.x();
  r.hit = m.sample(1).velocity_world.norm() > 0.01 * speed;
  if (b == 0.0) {
    r.energy_expected = -(1.0 - e * e) * mb / (ma + mb);
    const double vb_ref = (1.0 + e) * ma / (ma + mb) * speed;
    r.target_speed_error = (vb - vb_ref) / vb_ref;
  }
  r.failure = m.failure();
  return r;
}

// ---- cluster -----------------------------------------------------------------------------

struct ClusterRun {
  std::string not_run, failure;
  double max_rise_step = NAN;  // largest rise of the total energy over one step / E_in
  double total_rise = NAN;     // sum of the rises / E_in
  double final_change = NAN;   // (E_end - E_0) / E_in
  double max_overlap_m = NAN;
  double all_asleep_s = NAN, last_moving_s = NAN;
  std::size_t asleep_end = 0;
  std::size_t off_board = 0;  // stones below the board's top at the end (fell off)
  double cost_ns = NAN;
  // Over the steps that end within the first second (the block is struck and settles: ours
  // rests within it, the peers keep paying after it), ns per step.
  double cost_first_second_ns = NAN;
  std::vector<std::pair<std::string, long>> work_counters;  // ManyMethod::work_counters
};

ClusterRun run_cluster(ManyMethod& m, const ManyScene& s, double dt) {
  ClusterRun r;
  try {
    m.reset(s, dt);
  } catch (const ContactNotRun& e) {
    r.not_run = e.what();
    return r;
  }
  const std::size_t n = s.stones.size();
  auto total_energy = [&]() {
    double e = 0.0;
    for (std::size_t i = 0; i < n; ++i) e += stone_energy(s, i, m.sample(i));
    return e;
  };
  // The energy brought in: the thrown stone's kinetic energy plus its height above rest.
  const std::size_t thrown = n - 1;
  const ContactSample t0 = m.sample(thrown);
  const double e_in = stone_energy(s, thrown, t0) - (-s.spec(thrown).mass_kg * s.gravity_world.z() *
                                                     s.spec(thrown).half_height_m);
  const double e0 = total_energy();
  double prev = e0;
  r.max_rise_step = 0.0;
  r.total_rise = 0.0;
  r.max_overlap_m = 0.0;
  double cost = 0.0, cost_first_second = 0.0;
  long steps_first_second = 0;
  const long steps = steps_of(s, dt);
  for (long k = 1; k <= steps; ++k) {
    const auto c0 = Clock::now();
    m.advance();
    const double step_ns = std::chrono::duration<double, std::nano>(Clock::now() - c0).count();
    cost += step_ns;
    if (k * dt <= 1.0 + 1e-9) {
      cost_first_second += step_ns;
      ++steps_first_second;
    }
    const double e = total_energy();
    if (e > prev) {
      r.max_rise_step = std::max(r.max_rise_step, (e - prev) / e_in);
      r.total_rise += (e - prev) / e_in;
    }
    prev = e;
    bool all_asleep = true, moving = false;
    std::vector<ContactSample> smp(n);
    for (std::size_t i = 0; i < n; ++i) {
      smp[i] = m.sample(i);
      if (!m.asleep(i)) all_asleep = false;
      if (smp[i].velocity_world.norm() + s.spec(i).half_width_m * smp[i].omega_world.norm() > 1e-3)
        moving = true;
    }
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        r.max_overlap_m =
            std::max(r.max_overlap_m, lens_overlap_m(s.spec(i), smp[i], s.spec(j), smp[j]));
    if (all_asleep && std::isnan(r.all_asleep_s)) r.all_asleep_s = k * dt;
    if (moving) r.last_moving_s = k * dt;
  }
  for (std::size_t i = 0; i < n; ++i) {
    r.asleep_end += m.asleep(i) ? 1 : 0;
    r.off_board += m.sample(i).position_world.z() < 0.0 ? 1 : 0;
  }
  r.final_change = (prev - e0) / e_in;
  r.work_counters = m.work_counters();
  r.cost_ns = cost / steps;
  if (steps_first_second > 0) r.cost_first_second_ns = cost_first_second / steps_first_second;
  r.failure = m.failure();
  return r;
}

// ---- drops (events against N) --------------------------------------------------------

struct DropsRun {
  std::string not_run, failure;
  long events = 0;      // reported over the run (deterministic: same in every repetition)
  long work = -1;       // integration and search work over the run
  double run_ns = NAN;  // the whole run, median of the repetitions
  int reps = 0;
  std::size_t asleep_end = 0;
};

DropsRun run_drops(ManyMethod& m, const ManyScene& s, double dt, double budget_s) {
  DropsRun r;
  const long steps = steps_of(s, dt);
  std::vector<double> runs;
  double spent = 0.0;
  while (runs.size() < 3 || (spent < budget_s && runs.size() < 200)) {
    try {
      m.reset(s, dt);
    } catch (const ContactNotRun& e) {
      r.not_run = e.what();
      return r;
    }
    const long events0 = m.events_reported();
    if (events0 < 0) {
      r.not_run = "no events";
      return r;
    }
    const auto t0 = Clock::now();
    for (long k = 0; k < steps; ++k) m.advance();
    const double ns = std::chrono::duration<double, std::nano>(Clock::now() - t0).count();
    runs.push_back(ns);
    spent += ns * 1e-9;
    r.events = m.events_reported() - events0;
  }
  r.run_ns = median(runs);
  r.reps = static_cast<int>(runs.size());
  r.work = m.work_done();
  for (std::size_t i = 0; i < s.stones.size(); ++i) r.asleep_end += m.asleep(i) ? 1 : 0;
  r.failure = m.failure();
  return r;
}

std::string time_or_never(double t, bool has_sleep) {
  if (!has_sleep) return "no sleep";
  if (std::isnan(t)) return "never";
  char b[32];
  std::snprintf(b, sizeof b, "%.3g s", t);
  return b;
}

int run(const Options& o) {
  if (!make_output_folder("many_benchmark", o.out)) return 1;
  init_many_peers();
  std::vector<std::unique_ptr<ManyMethod>> methods;
  std::vector<std::unique_ptr<ManyMethod>> all;
  all.push_back(make_ours_many(o.nonsmooth_step_s, o.joint_solve, o.hold_check));
  all.push_back(make_bullet_many());
  all.push_back(make_ode_many());
  all.push_back(make_mujoco_many());
  // Every name asked for must be a method: an unknown one is an error, not an empty run.
  std::stringstream asked(o.methods);
  for (std::string name; std::getline(asked, name, ',');) {
    const bool known =
        std::any_of(all.begin(), all.end(), [&](const auto& m) { return m->name() == name; });
    if (!known) {
      std::string names;
      for (const auto& m : all) names += (names.empty() ? "" : ", ") + m->name();
      std::cerr << "many_benchmark: --methods: unknown method '" << name
                << "' (the methods: " << names << ")\n";
      return 2;
    }
  }
  for (auto& m : all)
    if (("," + o.methods + ",").find("," + m->name() + ",") != std::string::npos)
      methods.push_back(std::move(m));

  Csv csv(o.out + "/many_results.csv");
  std::ostringstream md, cost_dat;
  const double dt60 = 1.0 / 60.0;
  const double rest_duration = o.quick ? 2.0 : 10.0;

  // ---- rest
  std::map<std::string, std::map<int, RestRun>> rest;
  const std::vector<int>& counts = o.counts;
  for (const int n : counts) {
    const ManyScene s = resting_board(n, rest_duration);
    for (auto& m : methods) {
      std::cerr << "many_benchmark: rest N = " << n << ", " << m->name() << "\n";
      const RestRun r = run_rest(*m, s, dt60, o);
      rest[m->name()][n] = r;
      const std::string sec = "rest";
      if (!r.not_run.empty()) {
        csv.note(sec, s.name, m->name(), dt60, n, "not_run", r.not_run);
        continue;
      }
      csv.put(sec, s.name, m->name(), dt60, n, "cost_per_step_ns", r.cost_ns);
      csv.put(sec, s.name, m->name(), dt60, n, "cost_per_step_last_second_ns", r.cost_last_ns);
      csv.put(sec, s.name, m->name(), dt60, n, "repetitions", r.reps);
      csv.put(sec, s.name, m->name(), dt60, n, "max_horizontal_displacement_m", r.max_horizontal_m);
      csv.put(sec, s.name, m->name(), dt60, n, "max_vertical_displacement_m", r.max_vertical_m);
      csv.put(sec, s.name, m->name(), dt60, n, "max_rotation_rad", r.max_rotation_rad);
      csv.put(sec, s.name, m->name(), dt60, n, "max_rim_speed_mps", r.max_speed_mps);
      csv.put(sec, s.name, m->name(), dt60, n, "max_rim_speed_last_second_mps",
              r.max_speed_last_mps);
      csv.put(sec, s.name, m->name(), dt60, n, "asleep_at_end", r.asleep_end);
      csv.put(sec, s.name, m->name(), dt60, n, "all_asleep_s", r.all_asleep_s);
      csv.put(sec, s.name, m->name(), dt60, n, "last_moving_s", r.last_moving_s);
      if (r.work >= 0) csv.put(sec, s.name, m->name(), dt60, n, "work_done", r.work);
      if (!r.failure.empty()) csv.note(sec, s.name, m->name(), dt60, n, "failure", r.failure);
    }
  }

  md << "### Resting stones: cost per step (dt = 1/60 s, " << rest_duration << " s)\n\n"
     << "Median over repetitions of the mean cost per step (ours: per `advance_to`); in "
        "brackets the last second's, when every stone that can sleep is asleep.\n\n"
     << "| method |";
  for (const int n : counts) md << " N = " << n << " |";
  md << " N = " << counts.back() << " / N = " << counts.front() << " (last second) |\n|---|";
  for (std::size_t k = 0; k <= counts.size(); ++k) md << "---|";
  md << "\n";
  for (auto& m : methods) {
    md << "| " << m->name() << " |";
    for (const int n : counts) {
      const RestRun& r = rest[m->name()][n];
      if (!r.not_run.empty())
        md << " " << r.not_run << " |";
      else
        md << " " << time_text(r.cost_ns) << " (" << time_text(r.cost_last_ns) << ") |";
    }
    const RestRun &a = rest[m->name()][counts.front()], &z = rest[m->name()][counts.back()];
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.3g", z.cost_last_ns / a.cost_last_ns);
    md << " " << ratio << " |\n";
  }
  // Per peer: how much more a step costs than ours, on the full board.
  const RestRun& ours361 = rest["ours"][counts.back()];
  md << "\nFull board (N = 361), peer's cost per step over ours per `advance_to` (the issue's "
        "goal: >= 1000x):";
  for (auto& m : methods) {
    if (!m->is_peer()) continue;
    const RestRun& r = rest[m->name()][counts.back()];
    char b[64];
    std::snprintf(b, sizeof b, " %s %.3gx (last second %.3gx);", m->name().c_str(),
                  r.cost_ns / ours361.cost_ns, r.cost_last_ns / ours361.cost_last_ns);
    md << b;
  }
  md << "\n\n### Resting stones: creep and jitter (dt = 1/60 s, " << rest_duration << " s)\n\n"
     << "Largest over all stones and all steps: horizontal and vertical displacement from the "
        "pose set down, rotation, rim speed |v| + a |w| (whole run, last second); stones asleep "
        "at the end; first time every stone was asleep; last time any stone's rim speed "
        "exceeded 1 mm/s.\n\n"
     << "| N | method | horizontal | vertical | rotation (rad) | speed (m/s) | speed, last "
        "second | asleep at end | all asleep at | last > 1 mm/s at |\n"
     << "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const int n : counts) {
    for (auto& m : methods) {
      const RestRun& r = rest[m->name()][n];
      if (!r.not_run.empty()) continue;
      md << "| " << n << " | " << m->name() << (r.failure.empty() ? "" : " (" + r.failure + ")")
         << " | " << sci(r.max_horizontal_m) << " m | " << sci(r.max_vertical_m) << " m | "
         << sci(r.max_rotation_rad) << " | " << sci(r.max_speed_mps) << " | "
         << sci(r.max_speed_last_mps) << " | " << r.asleep_end << " / " << n << " | "
         << time_or_never(r.all_asleep_s, m->has_sleep()) << " | "
         << (std::isnan(r.last_moving_s) ? "never" : num(r.last_moving_s) + " s") << " |\n";
    }
  }
  if (rest["ours"][counts.back()].work >= 0)
    md << "\nOurs: integration and search work over the full board's run: "
       << rest["ours"][counts.back()].work
       << " (flight steps, searches, impacts, contact steps).\n";
  for (auto& m : methods) {
    cost_dat << "\"" << m->name() << "\"\n";
    for (const int n : counts) {
      const RestRun& r = rest[m->name()][n];
      if (r.not_run.empty()) cost_dat << n << " " << r.cost_ns << " " << r.cost_last_ns << "\n";
    }
    cost_dat << "\n\n";
  }

  // ---- collisions
  const std::vector<double> speeds =
      o.quick ? std::vector<double>{1.0} : std::vector<double>{0.3, 1.0, 3.0};
  const std::vector<double> dts = o.quick ? std::vector<double>{1.0 / 60, 1.0 / 1000}
                                          : std::vector<double>{1.0 / 60, 1.0 / 240, 1.0 / 1000};
  struct Kind {
    Colour target;
    bool oblique;
  };
  const std::vector<Kind> kinds = {
      {Colour::white, false}, {Colour::black, false}, {Colour::white, true}};
  md << "\n### Two-stone collisions (free in the air, no gravity)\n\n"
     << "A black stone, flat, at speed v along +x into a resting stone (rims facing); oblique: "
        "the target offset across by half the sum of the radii (30 degrees). Material e* = "
        "0.5, mu = 0.3 for every pair. Momentum error |p1 - p0| / |p0| and energy change "
        "(E1 - E0) / E0 once the stones are apart; head-on, the frictionless closed form loses "
        "(1 - e^2) m_B / (m_A + m_B) of E0 and gives the target (1 + e) m_A / (m_A + m_B) v. "
        "Overlap: the largest lens-lens penetration in any step. \"missed\": the target never "
        "moved (the stones passed through each other between two steps).\n\n"
     << "| collision | v (m/s) | dt (s) | method | momentum error | energy change (expected) | "
        "target speed error | max overlap |\n|---|---|---|---|---|---|---|---|\n";
  bool ours_row_done = false;
  for (const Kind& kd : kinds) {
    for (const double v : speeds) {
      for (const double dt : dts) {
        const double b =
            kd.oblique ? 0.5 * (black_stone().half_width_m + white_stone().half_width_m) : 0.0;
        const ManyScene s = two_stone_collision(kd.target, v, b, dt);
        for (auto& m : methods) {
          const CollisionRun r = run_collision(*m, s, dt, b, v);
          const std::string sec = "collision", scene = s.name + "_v" + num(v);
          if (!r.not_run.empty()) {
            csv.note(sec, scene, m->name(), dt, 2, "not_run", r.not_run);
            if (!ours_row_done) {
              md << "| all | all | all | " << m->name() << " | " << r.not_run << " | | | |\n";
              ours_row_done = true;
            }
            continue;
          }
          csv.put(sec, scene, m->name(), dt, 2, "momentum_error", r.momentum_error);
          csv.put(sec, scene, m->name(), dt, 2, "energy_change", r.energy_change);
          csv.put(sec, scene, m->name(), dt, 2, "energy_change_expected", r.energy_expected);
          csv.put(sec, scene, m->name(), dt, 2, "target_speed_error", r.target_speed_error);
          csv.put(sec, scene, m->name(), dt, 2, "max_overlap_m", r.max_overlap_m);
          csv.put(sec, scene, m->name(), dt, 2, "hit", r.hit ? 1 : 0);
          md << "| " << s.name << " | " << num(v) << " | " << dt_text(dt) << " | " << m->name()
             << (r.failure.empty() ? "" : " (" + r.failure + ")") << " | ";
          if (!r.hit) {
            md << "missed | " << sci(r.energy_change) << " | - | " << sci(r.max_overlap_m)
               << " m |\n";
            continue;
          }
          md << sci(r.momentum_error) << " | " << sci(r.energy_change) << " ("
             << (std::isnan(r.energy_expected) ? "< 0" : sci(r.energy_expected)) << ") | "
             << sci(r.target_speed_error) << " | " << sci(r.max_overlap_m) << " m |\n";
        }
      }
    }
  }

  // ---- cluster
  const std::vector<double> cluster_dts =
      o.quick ? std::vector<double>{1.0 / 60} : std::vector<double>{1.0 / 60, 1.0 / 240};
  const ManyScene cl = thrown_into_cluster(o.quick ? 2.0 : 5.0);
  md << "\n### A stone thrown into a cluster\n\n"
     << cl.description << "; " << cl.duration_s
     << " s. Energy figures relative to the energy brought in (the thrown stone's kinetic "
        "energy and height above rest): the largest rise of the total energy over one step, "
        "the sum of all rises, the change at the end; the largest lens-lens overlap of any "
        "pair in any step; sleep and stillness as above.\n\n"
     << "| dt (s) | method | largest rise | sum of rises | change at end | max overlap | asleep "
        "at end | all asleep at | last > 1 mm/s at | off the board at end | cost per step | cost "
        "per step, first 1 s |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const double dt : cluster_dts) {
    for (auto& m : methods) {
      std::cerr << "many_benchmark: cluster dt = " << dt_text(dt) << ", " << m->name() << "\n";
      const ClusterRun r = run_cluster(*m, cl, dt);
      const std::string sec = "cluster";
      if (!r.not_run.empty()) {
        csv.note(sec, cl.name, m->name(), dt, cl.stones.size(), "not_run", r.not_run);
        md << "| " << dt_text(dt) << " | " << m->name() << " | " << r.not_run
           << " | | | | | | | | | |\n";
        continue;
      }
      const std::size_t n = cl.stones.size();
      csv.put(sec, cl.name, m->name(), dt, n, "max_energy_rise_per_step", r.max_rise_step);
      csv.put(sec, cl.name, m->name(), dt, n, "sum_energy_rises", r.total_rise);
      csv.put(sec, cl.name, m->name(), dt, n, "energy_change_at_end", r.final_change);
      csv.put(sec, cl.name, m->name(), dt, n, "max_overlap_m", r.max_overlap_m);
      csv.put(sec, cl.name, m->name(), dt, n, "asleep_at_end", r.asleep_end);
      csv.put(sec, cl.name, m->name(), dt, n, "all_asleep_s", r.all_asleep_s);
      csv.put(sec, cl.name, m->name(), dt, n, "last_moving_s", r.last_moving_s);
      csv.put(sec, cl.name, m->name(), dt, n, "cost_per_step_ns", r.cost_ns);
      csv.put(sec, cl.name, m->name(), dt, n, "cost_per_step_first_second_ns",
              r.cost_first_second_ns);
      csv.put(sec, cl.name, m->name(), dt, n, "off_board_at_end", r.off_board);
      for (const auto& [name, value] : r.work_counters) {
        csv.put(sec, cl.name, m->name(), dt, n, name, value);
        std::cerr << "many_benchmark:   " << name << " " << value << "\n";
      }
      md << "| " << dt_text(dt) << " | " << m->name()
         << (r.failure.empty() ? "" : " (" + r.failure + ")") << " | " << sci(r.max_rise_step)
         << " | " << sci(r.total_rise) << " | " << sci(r.final_change) << " | "
         << sci(r.max_overlap_m) << " m | " << r.asleep_end << " / " << n << " | "
         << time_or_never(r.all_asleep_s, m->has_sleep()) << " | "
         << (std::isnan(r.last_moving_s) ? "never" : num(r.last_moving_s) + " s") << " | "
         << r.off_board << " | " << time_text(r.cost_ns) << " | "
         << time_text(r.cost_first_second_ns) << " |\n";
    }
  }

  // ---- drops: what an event costs as N grows (ours: the engines have no events to count)
  const double drops_duration = 1.0;
  md << "\n### Events against the number of stones (ours)\n\n"
     << "N stones dropped flat from 2 to 20 mm (staggered heights) onto a 19 x 19 grid of "
        "twice the Go pitch, so that no two touch; each bounces and comes to rest exactly; "
        "stone-stone contact on (every awake stone is checked against its neighbours). "
     << drops_duration
     << " s at dt = 1/60 s; run time: median over repetitions. Cost per event is the whole "
        "run's time over the events reported (impacts, contact changes, rests), so it includes "
        "the flights sampled between events. The issue's goal: cost per event grows at most as "
        "log N.\n\n"
     << "| N | events | work | asleep at end | run time | per advance_to | per event | per event / "
        "N = 1's | log2(N) + 1 |\n|---|---|---|---|---|---|---|---|---|\n";
  double per_event_1 = NAN;
  for (auto& m : methods) {
    if (m->is_peer()) continue;
    for (const int n : counts) {
      const ManyScene s = dropped_grid(n, drops_duration);
      std::cerr << "many_benchmark: drops N = " << n << ", " << m->name() << "\n";
      const DropsRun r = run_drops(*m, s, dt60, o.quick ? 0.1 : 1.0);
      const std::string sec = "drops";
      if (!r.not_run.empty()) {
        csv.note(sec, s.name, m->name(), dt60, n, "not_run", r.not_run);
        md << "| " << n << " | " << r.not_run << " | | | | | | | |\n";
        continue;
      }
      const long steps = steps_of(s, dt60);
      const double per_event = r.events > 0 ? r.run_ns / r.events : NAN;
      if (std::isnan(per_event_1)) per_event_1 = per_event;
      csv.put(sec, s.name, m->name(), dt60, n, "events", r.events);
      csv.put(sec, s.name, m->name(), dt60, n, "work_done", r.work);
      csv.put(sec, s.name, m->name(), dt60, n, "asleep_at_end", r.asleep_end);
      csv.put(sec, s.name, m->name(), dt60, n, "run_ns", r.run_ns);
      csv.put(sec, s.name, m->name(), dt60, n, "repetitions", r.reps);
      csv.put(sec, s.name, m->name(), dt60, n, "cost_per_advance_ns", r.run_ns / steps);
      csv.put(sec, s.name, m->name(), dt60, n, "cost_per_event_ns", per_event);
      if (!r.failure.empty()) csv.note(sec, s.name, m->name(), dt60, n, "failure", r.failure);
      char ratio[64];
      std::snprintf(ratio, sizeof ratio, "%.3g | %.3g", per_event / per_event_1,
                    std::log2(static_cast<double>(n)) + 1.0);
      md << "| " << n << " | " << r.events << " | " << r.work << " | " << r.asleep_end << " / " << n
         << " | " << time_text(r.run_ns) << " | " << time_text(r.run_ns / steps) << " | "
         << time_text(per_event) << " | " << ratio << " |\n";
    }
  }

  // ---- settings
  std::ostringstream st;
  const ManyScene full = resting_board(361, 1.0);
  for (auto& m : methods) {
    m->reset(full, dt60);
    st << "#### " << m->name() << ": " << m->version()
       << "\n\n| setting | value | documented in |\n"
       << "|---|---|---|\n";
    for (const Setting& x : m->settings())
      st << "| " << x.name << " | " << x.value << " | " << x.documentation << " |\n";
    st << "\n";
  }
  std::ofstream(o.out + "/many_tables.md") << md.str();
  std::ofstream(o.out + "/many_settings.md") << st.str();
  std::ofstream(o.out + "/many_cost.dat") << cost_dat.str();
  methods.clear();
  shutdown_many_peers();
  std::cerr << "many_benchmark: wrote " << o.out << "/many_results.csv, many_tables.md, "
            << "many_settings.md, many_cost.dat\n";
  return 0;
}

}  // namespace
}  // namespace vg_bench

int main(int argc, char** argv) {
  std::ostringstream limit_s;
  limit_s << virtual_go::kNonsmoothLargestStepS;
  const std::string usage =
      "usage: many_benchmark [--quick] [--methods ours,bullet,ode,mujoco] [--counts 1,10,100,361] "
      "[--out DIR] [--nonsmooth-step H_S] [--joint-solve] [--no-hold-check]\n"
      "  The many-stone benchmark (issue 15): resting boards, two-stone collisions, a stone "
      "thrown\n"
      "  into a cluster, events against the number of stones. --out DIR (made if missing) gets\n"
      "  many_results.csv, many_tables.md, many_settings.md, many_cost.dat; --nonsmooth-step: the\n"
      "  island sub-step h in s, at most the core's verified limit and default, " +
      limit_s.str() +
      " s (0: the\n  default); --joint-solve: ours with the joint solve "
      "(NonsmoothContactOptions::joint_solve,\n  off by default); --no-hold-check: ours without "
      "the islands' hold check\n  (NonsmoothContactOptions::hold_check, on by default). The joint "
      "solve's counts and the\n  refused rests go to the results. scripts/benchmark.sh --many-only "
      "runs it.\n";
  vg_bench::Options o;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--help" || a == "-h") {
        std::cout << usage;
        return 0;
      } else if (a == "--quick") {
        o.quick = true;
      } else if (a == "--methods" && i + 1 < argc) {
        o.methods = argv[++i];
      } else if (a == "--counts" && i + 1 < argc) {
        o.counts.clear();
        std::stringstream list(argv[++i]);
        for (std::string c; std::getline(list, c, ',');) o.counts.push_back(std::stoi(c));
      } else if (a == "--out" && i + 1 < argc) {
        o.out = argv[++i];
      } else if (a == "--nonsmooth-step" && i + 1 < argc) {
        o.nonsmooth_step_s = std::stod(argv[++i]);
      } else if (a == "--joint-solve") {
        o.joint_solve = true;
      } else if (a == "--no-hold-check") {
        o.hold_check = false;
      } else {
        std::cerr << "many_benchmark: unknown or incomplete option '" << a << "'\n" << usage;
        return 2;
      }
    }
  } catch (const std::exception&) {
    std::cerr << "many_benchmark: --counts takes whole numbers and --nonsmooth-step a number\n"
              << usage;
    return 2;
  }
  if (!(o.nonsmooth_step_s >= 0.0 && o.nonsmooth_step_s <= virtual_go::kNonsmoothLargestStepS)) {
    std::cerr << "many_benchmark: --nonsmooth-step must be between 0 (the default) and "
              << limit_s.str() << " s, got " << o.nonsmooth_step_s << "\n";
    return 2;
  }
  return vg_bench::run(o);
}
