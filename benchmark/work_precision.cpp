// Work-precision benchmark: every integrator of the virtual_go core and the peer engines (Bullet,
// ODE, MuJoCo) on the same size-33 slate stone, errors against the closed form, cost per step.
// Writes results.csv, tables.md, goals.md, headline.md and plot data into --out.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "bench.h"
#include "output_folder.h"
#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/flight/exact_motion.h"
#include "virtual_go/flight/flight_cache.h"
#include "virtual_go/geometry/rotation.h"
#include "virtual_go/go/stone.h"

namespace vg = virtual_go;
using vg_bench::Method;
using vg_bench::Sample;
using vg_bench::Scenario;

namespace {

// ---- our integrators behind the same interface as the peers ----
class OursMethod : public Method {
 public:
  explicit OursMethod(std::string name) : name_(std::move(name)) {}
  std::string name() const override { return name_; }
  bool is_peer() const override { return false; }
  void reset(const Scenario& s, double dt) override {
    scenario_ = &s;
    integrator_ = vg::make_integrator(name_, s.setup);
    state_ = s.initial;
    cache_.invalidate();  // a new flight
    dt_ = dt;
  }
  void step() override { integrator_->advance(state_, dt_, cache_); }
  Sample sample() const override {
    return Sample{state_.position_world, state_.orientation, state_.velocity_world,
                  scenario_->setup.model.angular_velocity_world(state_.orientation,
                                                                state_.angular_momentum_world)};
  }

 private:
  std::string name_;
  const Scenario* scenario_ = nullptr;
  std::unique_ptr<vg::Integrator> integrator_;
  vg::RigidBodyState state_;
  vg::FlightCache cache_;  // the stone's: what the integrator carries between its steps
  double dt_ = 0.0;
};

struct Options {
  std::string out = ".";
  std::vector<std::string> scenarios;  // empty: all
  long max_timed_steps = 1 << 14;      // steps per timed repetition
  double budget_seconds = 0.03;        // target timed time per (method, dt) after warm-up
  int min_reps = 5, max_reps = 201;
  bool quick = false;
};

struct Result {
  std::string scenario, method, dt_label, status = "ok";
  double dt = 0.0;
  long steps = 0;
  double ori_T = NAN, ori_max = 0, pos_T = NAN, pos_max = 0;
  double energy_T = NAN, energy_max = 0, rot_energy_T = NAN, rot_energy_max = 0;
  double momentum_T = NAN, momentum_max = 0;
  double ns_per_step = NAN, ns_per_step_min = NAN;
  long timed_steps = 0;
  int reps = 0;
  bool peer = false;
  bool ok() const { return status == "ok"; }
  double ns_per_sim_second() const { return ns_per_step / dt; }
};

struct Invariants {
  double energy, rot_energy;
  Eigen::Vector3d momentum;
};

Invariants invariants(const Scenario& s, const Eigen::Vector3d& x, const Eigen::Quaterniond& q,
                      const Eigen::Vector3d& v, const Eigen::Vector3d& w) {
  // L = R I R^T omega with the scenario's model (isotropic for constant_omega, matching the
  // isotropic inertia the peers get in that scenario).
  const Eigen::Vector3d l = s.setup.model.angular_momentum_world(q.normalized(), w);
  const double rot = 0.5 * w.dot(l);
  const double trans = 0.5 * s.mass * v.squaredNorm() - s.mass * s.setup.gravity_world.dot(x);
  return Invariants{rot + trans, rot, l};
}

bool finite(const Sample& smp) {
  return smp.position_world.allFinite() && smp.orientation.coeffs().allFinite() &&
         smp.velocity_world.allFinite() && smp.omega_world.allFinite();
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

void measure_accuracy(Method& method, const Scenario& s, Result& r) {
  const vg::ExactMotion reference(s.setup, s.initial);
  const Invariants i0 = invariants(s, s.initial.position_world, s.initial.orientation,
                                   s.initial.velocity_world, s.initial_omega_world);
  method.reset(s, r.dt);
  for (long k = 1; k <= r.steps; ++k) {
    try {
      method.step();
    } catch (const vg::IntegrationError& e) {
      r.status = k == 1 ? "not run: step too large"
                        : "stopped at t = " + fmt("%.4g", k * r.dt) + " s: step too large";
      return;
    }
    const Sample smp = method.sample();
    if (const std::string f = method.failure(); !f.empty()) {
      r.status = f + " at t = " + fmt("%.4g", k * r.dt) + " s";
      return;
    }
    if (!finite(smp)) {
      r.status = "diverged (non-finite state) at t = " + fmt("%.4g", k * r.dt) + " s";
      return;
    }
    const vg::RigidBodyState ref = reference.state_at(static_cast<double>(k) * r.dt);
    const double ori = vg::orientation_error(ref.orientation, smp.orientation);
    const double pos = (smp.position_world - ref.position_world).norm();
    const Invariants inv =
        invariants(s, smp.position_world, smp.orientation, smp.velocity_world, smp.omega_world);
    const double de = std::abs(inv.energy - i0.energy) / std::abs(i0.energy);
    const double drot = std::abs(inv.rot_energy - i0.rot_energy) / i0.rot_energy;
    const double dl = (inv.momentum - i0.momentum).norm() / i0.momentum.norm();
    r.ori_max = std::max(r.ori_max, ori);
    r.pos_max = std::max(r.pos_max, pos);
    r.energy_max = std::max(r.energy_max, de);
    r.rot_energy_max = std::max(r.rot_energy_max, drot);
    r.momentum_max = std::max(r.momentum_max, dl);
    if (k == r.steps) {
      r.ori_T = ori;
      r.pos_T = pos;
      r.energy_T = de;
      r.rot_energy_T = drot;
      r.momentum_T = dl;
    }
  }
}

double time_once(Method& method, const Scenario& s, double dt, long steps) {
  method.reset(s, dt);  // not timed: world creation, model loading
  const auto t0 = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k) {
    method.step();
    benchmark::ClobberMemory();  // each step's result must reach memory, no hoisting
  }
  const auto t1 = std::chrono::steady_clock::now();
  Sample smp = method.sample();
  benchmark::DoNotOptimize(smp);
  return std::chrono::duration<double, std::nano>(t1 - t0).count() / static_cast<double>(steps);
}

void measure_time(Method& method, const Scenario& s, const Options& o, Result& r) {
  // A fixed number of steps for every dt: short runs (300 steps at 1/30) would time mostly the
  // start-up; the motion past T is the same motion. Falls back to T when that goes wrong.
  r.timed_steps = o.max_timed_steps;
  if (r.timed_steps > r.steps) {  // within T the run is known to be fine; past T check it
    method.reset(s, r.dt);
    try {
      for (long k = 0; k < r.timed_steps; ++k) method.step();
      if (!finite(method.sample()) || !method.failure().empty()) r.timed_steps = r.steps;
    } catch (const std::exception&) {
      r.timed_steps = r.steps;
    }
  }
  const double warm = time_once(method, s, r.dt, r.timed_steps);  // warm caches, size reps
  const double per_rep = warm * 1e-9 * static_cast<double>(r.timed_steps);
  r.reps = static_cast<int>(std::clamp(o.budget_seconds / std::max(per_rep, 1e-9),
                                       static_cast<double>(o.min_reps),
                                       static_cast<double>(o.max_reps)));
  std::vector<double> samples;
  for (int k = 0; k < r.reps; ++k) samples.push_back(time_once(method, s, r.dt, r.timed_steps));
  std::sort(samples.begin(), samples.end());
  const size_t n = samples.size();
  r.ns_per_step = n % 2 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
  r.ns_per_step_min = samples.front();
}

std::vector<Scenario> make_scenarios() {
  vg::StoneSpec spec;
  spec.size_number = 33;
  spec.material = "slate";
  const vg::Stone stone = vg::make_stone(spec);
  const vg::MassProperties& mp = stone.mass_properties;
  const vg::MotionModel rigid(vg::MotionModelKind::rigid_body, mp);
  const vg::MotionModel article(vg::MotionModelKind::constant_omega, mp);
  const Eigen::Vector3d g = vg::kStandardGravity;

  vg::RigidBodyState start;
  start.position_world = Eigen::Vector3d(0.0, 0.0, 0.5);
  start.velocity_world = Eigen::Vector3d(0.3, -0.2, 2.0);
  // A non-trivial initial orientation: no body axis along a world axis.
  start.orientation = vg::rotation_exp(Eigen::Vector3d(0.3, -0.5, 0.7));
  const Eigen::Vector3d omega_tumble(20.0, 5.0, 40.0);  // |omega| = 45 rad/s
  const double speed = omega_tumble.norm();
  const Eigen::Vector3d axis = start.orientation * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d across = start.orientation * Eigen::Vector3d::UnitX();

  auto make = [&](const std::string& name, const std::string& what, const vg::MotionModel& model,
                  const Eigen::Vector3d& omega) {
    Scenario s{name,
               what,
               vg::MotionSetup{model, g},
               vg::with_angular_velocity_world(model, start, omega),
               omega,
               mp.mass(),
               model.kind() == vg::MotionModelKind::constant_omega
                   ? Eigen::Vector3d::Constant(model.isotropic_moment())
                   : mp.principal_moments_body(),
               10.0};
    return s;
  };
  return {
      make("tumble", "rigid_body, gravity, world omega (20, 5, 40) rad/s: off-axis, precessing",
           rigid, omega_tumble),
      make("spin", "rigid_body, gravity, omega 45 rad/s along the symmetry axis", rigid,
           speed * axis),
      make("flip", "rigid_body, gravity, omega 45 rad/s perpendicular to the symmetry axis", rigid,
           speed * across),
      make("article",
           "constant_omega (the article's model), gravity, world omega (20, 5, 40) rad/s; peers "
           "simulate a body with isotropic inertia trace(I)/3, whose omega is constant too",
           article, omega_tumble),
  };
}

struct Step {
  double dt;
  std::string label;
};

std::vector<Step> make_steps(bool quick) {
  // The two frame rates users pick, then powers of two down to 2^-16 s.
  std::vector<Step> steps{{1.0 / 30, "1/30"}, {1.0 / 60, "1/60"}};
  const int last = quick ? 10 : 16;
  for (int k = 5; k <= last; ++k)
    steps.push_back({std::ldexp(1.0, -k), "1/" + std::to_string(1 << k)});
  std::sort(steps.begin(), steps.end(), [](const Step& a, const Step& b) { return a.dt > b.dt; });
  return steps;
}

std::string sci(double v) {
  if (std::isnan(v)) return "-";
  if (v == 0.0) return "0";
  return fmt("%.2e", v);
}

void write_csv(const std::string& path, const std::vector<Result>& results) {
  std::ofstream f(path);
  f << "scenario,method,dt_label,dt_s,steps,status,ori_err_T_rad,ori_err_max_rad,pos_err_T_m,"
       "pos_err_max_m,energy_rel_T,energy_rel_max,rot_energy_rel_T,rot_energy_rel_max,"
       "momentum_rel_T,momentum_rel_max,ns_per_step_median,ns_per_step_min,ns_per_sim_s,"
       "timed_steps,repetitions\n";
  for (const Result& r : results) {
    auto g = [](double v) { return std::isnan(v) ? std::string() : fmt("%.6g", v); };
    f << r.scenario << "," << r.method << "," << r.dt_label << "," << fmt("%.17g", r.dt) << ","
      << r.steps << ",\"" << r.status << "\"," << g(r.ori_T) << "," << g(r.ok() ? r.ori_max : NAN)
      << "," << g(r.pos_T) << "," << g(r.ok() ? r.pos_max : NAN) << "," << g(r.energy_T) << ","
      << g(r.ok() ? r.energy_max : NAN) << "," << g(r.rot_energy_T) << ","
      << g(r.ok() ? r.rot_energy_max : NAN) << "," << g(r.momentum_T) << ","
      << g(r.ok() ? r.momentum_max : NAN) << "," << g(r.ns_per_step) << "," << g(r.ns_per_step_min)
      << "," << g(r.ok() ? r.ns_per_sim_second() : NAN) << "," << r.timed_steps << "," << r.reps
      << "\n";
  }
}

std::string table_header() {
  return "| method | dt (s) | orientation error at T (rad) | max over run (rad) | position error "
         "at T (m) | max rel. energy error | max rel. rotational energy error | max rel. "
         "momentum error | ns / step | us / simulated s |\n"
         "|---|---|---|---|---|---|---|---|---|---|\n";
}

std::string table_row(const Result& r) {
  std::ostringstream row;
  row << "| " << r.method << " | " << r.dt_label << " | ";
  if (!r.ok()) {
    row << r.status << " | | | | | | | |\n";
    return row.str();
  }
  row << sci(r.ori_T) << " | " << sci(r.ori_max) << " | " << sci(r.pos_T) << " | "
      << sci(r.energy_max) << " | " << sci(r.rot_energy_max) << " | " << sci(r.momentum_max)
      << " | " << fmt("%.1f", r.ns_per_step) << " | " << fmt("%.3g", r.ns_per_sim_second() / 1e3)
      << " |\n";
  return row.str();
}

void write_tables(const std::string& path, const std::vector<Scenario>& scenarios,
                  const std::vector<Result>& results) {
  std::ofstream f(path);
  for (const Scenario& s : scenarios) {
    f << "### " << s.name << "\n\n"
      << s.description << "; T = " << s.duration << " s. Every method at dt = 1/60 s:\n\n"
      << table_header();
    for (const Result& r : results) {
      if (r.scenario == s.name && r.dt_label == "1/60") f << table_row(r);
    }
    f << "\n<details><summary>All step sizes (" << s.name << ")</summary>\n\n" << table_header();
    for (const Result& r : results) {
      if (r.scenario == s.name) f << table_row(r);
    }
    f << "\n</details>\n\n";
  }
}

void write_plot_data(const std::string& out, const std::vector<Scenario>& scenarios,
                     const std::vector<Result>& results, const std::vector<std::string>& methods) {
  for (const Scenario& s : scenarios) {
    std::ofstream f(out + "/plot_" + s.name + ".dat");
    // One gnuplot data block per method (blocks separated by two blank lines), first line the
    // title; the error is floored at 1e-17 so a zero still shows on a log axis.
    for (const std::string& m : methods) {
      f << "\"" << m << "\"\n";
      for (const Result& r : results) {
        if (r.scenario != s.name || r.method != m || !r.ok() || std::isnan(r.ns_per_step)) continue;
        f << fmt("%.6g", std::max(r.ori_max, 1e-17)) << " " << fmt("%.6g", r.ns_per_sim_second())
          << " " << r.dt_label << "\n";
      }
      f << "\n\n";
    }
  }
}

const Result* find(const std::vector<Result>& results, const std::string& scenario,
                   const std::string& method, const std::string& dt_label) {
  for (const Result& r : results) {
    if (r.scenario == scenario && r.method == method && r.dt_label == dt_label) return &r;
  }
  return nullptr;
}

void write_goals(const std::string& out, const std::vector<Result>& results,
                 const std::vector<std::string>& methods) {
  std::ofstream f(out + "/goals.md");
  std::ofstream h(out + "/headline.md");
  const Result* exact = find(results, "tumble", "exact", "1/60");
  if (!exact || !exact->ok()) {
    f << "The tumble scenario with `exact` at dt = 1/60 s was not run; no goals evaluated.\n";
    return;
  }
  // Goal 1: accuracy at dt = 1/60.
  const bool exact_accurate = exact->ori_T <= 1e-12;
  double best_peer_60 = INFINITY;
  std::string best_peer_60_name, peer_lines;
  for (const Result& r : results) {
    if (r.scenario != "tumble" || r.dt_label != "1/60" || !r.peer) continue;
    const double e = r.ok() ? r.ori_T : INFINITY;
    peer_lines += "  - " + r.method + ": " + (r.ok() ? sci(r.ori_T) + " rad" : r.status) + "\n";
    if (e < best_peer_60) {
      best_peer_60 = e;
      best_peer_60_name = r.method;
    }
  }
  const bool peers_off = best_peer_60 > 1e-3;
  f << "1. **`exact` on tumble at dt = 1/60 s: orientation error <= 1e-12 rad after 10 s, every "
       "peer > 1e-3 rad.** `exact`: "
    << sci(exact->ori_T) << " rad (max over the run " << sci(exact->ori_max) << ") — "
    << (exact_accurate ? "met" : "MISSED") << ". Peers at the same dt:\n"
    << peer_lines << "  Best peer " << best_peer_60_name << " at " << sci(best_peer_60) << " rad — "
    << (peers_off ? "every peer is off by more than 1e-3 rad (met)" : "MISSED") << ".\n";

  // Goal 2: cost per step and per simulated second against the cheapest accurate peer.
  const bool cheap_step = exact->ns_per_step <= 30.0;
  const Result* cheapest = nullptr;
  for (const Result& r : results) {
    if (r.scenario != "tumble" || !r.peer || !r.ok() || std::isnan(r.ns_per_step)) continue;
    if (r.ori_max > 1e-3) continue;
    if (!cheapest || r.ns_per_sim_second() < cheapest->ns_per_sim_second()) cheapest = &r;
  }
  f << "2. **`exact` <= 30 ns per step and >= 10x cheaper per simulated second than the cheapest "
       "peer configuration reaching 1e-3 rad.** `exact` at dt = 1/60 s: "
    << fmt("%.1f", exact->ns_per_step) << " ns per step (fastest repetition "
    << fmt("%.1f", exact->ns_per_step_min) << " ns) — " << (cheap_step ? "met" : "MISSED") << "; "
    << fmt("%.3g", exact->ns_per_sim_second() / 1e3) << " us per simulated second.\n";
  double ratio = NAN;
  if (cheapest) {
    ratio = cheapest->ns_per_sim_second() / exact->ns_per_sim_second();
    f << "   Cheapest peer configuration whose orientation error stays <= 1e-3 rad over the whole "
         "10 s: "
      << cheapest->method << " at dt = " << cheapest->dt_label << " s ("
      << fmt("%.1f", cheapest->ns_per_step) << " ns per step, "
      << fmt("%.3g", cheapest->ns_per_sim_second() / 1e3) << " us per simulated second, max error "
      << sci(cheapest->ori_max) << " rad): `exact` is " << fmt("%.0f", ratio) << "x cheaper — "
      << (ratio >= 10 ? "met" : "MISSED") << ".\n";
  } else {
    f << "   No peer configuration reached 1e-3 rad over the run at any dt measured: the ratio is "
         "unbounded (met).\n";
  }
  // Per-peer cheapest accurate configuration, for the headline.
  f << "\n   Cheapest configuration of each method that keeps the tumble's orientation error <= "
       "1e-3 rad over 10 s:\n\n   | method | dt (s) | max error (rad) | ns / step | us / simulated "
       "s | cost vs `exact` at 1/60 |\n   |---|---|---|---|---|---|\n";
  for (const std::string& m : methods) {
    const Result* best = nullptr;
    for (const Result& r : results) {
      if (r.scenario != "tumble" || r.method != m || !r.ok() || std::isnan(r.ns_per_step)) continue;
      if (r.ori_max > 1e-3) continue;
      if (!best || r.ns_per_sim_second() < best->ns_per_sim_second()) best = &r;
    }
    if (!best) {
      f << "   | " << m << " | none reaches 1e-3 rad | | | | |\n";
      continue;
    }
    f << "   | " << m << " | " << best->dt_label << " | " << sci(best->ori_max) << " | "
      << fmt("%.1f", best->ns_per_step) << " | " << fmt("%.3g", best->ns_per_sim_second() / 1e3)
      << " | " << fmt("%.3g", best->ns_per_sim_second() / exact->ns_per_sim_second()) << "x |\n";
  }

  h << "- A tumbling size-33 slate stone (world angular velocity (20, 5, 40) rad/s, gravity on), "
       "10 s at dt = 1/60 s: the `exact` integrator ends "
    << sci(exact->ori_T) << " rad from the closed form; the best peer (" << best_peer_60_name
    << ") is off by " << sci(best_peer_60) << " rad.\n"
    << "- `exact` costs " << fmt("%.1f", exact->ns_per_step) << " ns per step ("
    << fmt("%.3g", exact->ns_per_sim_second() / 1e3) << " us per simulated second at 60 Hz).";
  if (cheapest) {
    h << " The cheapest peer configuration that stays within 1e-3 rad (" << cheapest->method
      << " at dt = " << cheapest->dt_label << " s) costs " << fmt("%.0f", ratio)
      << "x more per simulated second.";
  }
  h << "\n";
}

void print_usage() {
  std::printf(
      "usage: work_precision [--out DIR] [--scenario NAME]... [--quick] [--timed-steps N]\n"
      "                      [--budget SECONDS]\n"
      "Runs every method (ours: %s; bullet, bullet_grams, ode,\n"
      "ode_finite, mujoco_euler, mujoco_rk4) on the scenarios tumble, spin, flip, article for\n"
      "dt = 1/30, 1/60 and 2^-5 .. 2^-16 s; writes results.csv, tables.md, goals.md,\n"
      "headline.md, notes.md and plot_<scenario>.dat into DIR (default .).\n"
      "  --quick           dt only down to 2^-10 s (a smoke run)\n"
      "  --timed-steps N   steps per timed repetition (default 16384)\n"
      "  --budget S        timed seconds per method and dt (default 0.03; >= 5 repetitions)\n",
      vg::join(vg::integrator_names(), " ").c_str());
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "work_precision: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "-h" || a == "--help") {
      print_usage();
      return 0;
    } else if (a == "--out") {
      o.out = value();
    } else if (a == "--scenario") {
      o.scenarios.push_back(value());
    } else if (a == "--quick") {
      o.quick = true;
    } else if (a == "--timed-steps") {
      o.max_timed_steps = std::stol(value());
    } else if (a == "--budget") {
      o.budget_seconds = std::stod(value());
    } else {
      std::fprintf(stderr, "work_precision: unknown option %s (see --help)\n", a.c_str());
      return 2;
    }
  }

  if (!vg_bench::make_output_folder("work_precision", o.out)) return 1;
  vg_bench::init_peers();
  std::vector<std::string> notes;
  std::vector<std::unique_ptr<Method>> methods;
  for (const std::string& n : vg::integrator_names()) {
    methods.push_back(std::make_unique<OursMethod>(n));
  }
  methods.push_back(vg_bench::make_bullet(1.0, notes));
  methods.push_back(vg_bench::make_bullet(1e3, notes));
  methods.push_back(vg_bench::make_ode(false, notes));
  methods.push_back(vg_bench::make_ode(true, notes));
  methods.push_back(vg_bench::make_mujoco(false, notes));
  methods.push_back(vg_bench::make_mujoco(true, notes));
  std::vector<std::string> method_names;
  for (const auto& m : methods) method_names.push_back(m->name());

  std::vector<Scenario> scenarios;
  for (const Scenario& s : make_scenarios()) {
    if (o.scenarios.empty() ||
        std::find(o.scenarios.begin(), o.scenarios.end(), s.name) != o.scenarios.end()) {
      scenarios.push_back(s);
    }
  }
  const std::vector<Step> steps = make_steps(o.quick);

  std::vector<Result> results;
  const auto start = std::chrono::steady_clock::now();
  for (const Scenario& s : scenarios) {
    for (const auto& m : methods) {
      for (const Step& st : steps) {
        Result r;
        r.scenario = s.name;
        r.method = m->name();
        r.peer = m->is_peer();
        r.dt = st.dt;
        r.dt_label = st.label;
        r.steps = std::lround(s.duration / st.dt);
        try {
          measure_accuracy(*m, s, r);
          if (r.ok()) measure_time(*m, s, o, r);
        } catch (const std::exception& e) {
          r.status = std::string("failed: ") + e.what();
        }
        std::fprintf(stderr, "%-8s %-13s dt %-8s %-40s ori %-9s max %-9s %8.1f ns/step\n",
                     s.name.c_str(), r.method.c_str(), st.label.c_str(),
                     r.status.substr(0, 40).c_str(), sci(r.ori_T).c_str(), sci(r.ori_max).c_str(),
                     r.ns_per_step);
        results.push_back(r);
      }
    }
  }
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  methods.clear();  // the ODE worlds must go before dCloseODE
  vg_bench::shutdown_peers();

  write_csv(o.out + "/results.csv", results);
  write_tables(o.out + "/tables.md", scenarios, results);
  write_plot_data(o.out, scenarios, results, method_names);
  write_goals(o.out, results, method_names);
  std::ofstream n(o.out + "/notes.md");
  for (const std::string& line : notes) n << "- " << line << "\n";
  n << "- Timing: each (method, dt) is timed over " << o.max_timed_steps
    << " steps from the scenario's start (shorter or longer than T = 10 s; where the motion past "
       "T failed, over T only), after one warm-up repetition; repetitions sized to about "
    << o.budget_seconds << " s (at least " << o.min_reps << ", at most " << o.max_reps
    << "), median reported. Errors always cover the full T = 10 s, every step compared with the "
       "closed form. Whole run: "
    << fmt("%.0f", elapsed) << " s.\n";
  std::fprintf(stderr, "work_precision: %zu results in %.0f s, written to %s\n", results.size(),
               elapsed, o.out.c_str());
  return 0;
}
