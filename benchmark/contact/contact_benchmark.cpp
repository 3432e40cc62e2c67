// Contact benchmark: a size-33 slate stone dropped, tossed, slid and laid on the real board,
// simulated by ours and by Bullet, ODE and MuJoCo (each with its defaults and tuned for a body
// of this size), every method sampled on the same grid t_k = k dt for a sweep of dt; errors
// against the closed forms where they exist, physical checks (energy, penetration, jitter,
// rest) everywhere, cost per simulated second as the median of repetitions. Writes CSV,
// markdown tables, plot data and a headline into --out.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>

#include "../output_folder.h"
#include "contact_method.h"
#include "contact_report.h"
#include "trajectory_metrics.h"

using namespace vg_bench;

namespace {

struct Options {
  std::string out = ".";
  std::vector<std::string> scenarios, methods;  // empty: all
  int finest_exponent = 16;                     // dt down to 2^-finest
  double budget_seconds = 0.2;                  // timed seconds per (scenario, method, dt)
  int min_reps = 3, max_reps = 21;
  std::string trace;  // "scenario,method,dt_label": write that run's grid states to a CSV
  bool self_check = false;
};

struct Step {
  double dt;
  std::string label;
};

std::vector<Step> make_steps(int finest) {
  std::vector<Step> steps{{1.0 / 30, "1/30"}, {1.0 / 60, "1/60"}};
  for (int k = 5; k <= finest; ++k)
    steps.push_back({std::ldexp(1.0, -k), "1/" + std::to_string(1 << k)});
  std::sort(steps.begin(), steps.end(), [](const Step& a, const Step& b) { return a.dt > b.dt; });
  return steps;
}

bool finite(const ContactSample& s) {
  return s.position_world.allFinite() && s.orientation.coeffs().allFinite() &&
         s.velocity_world.allFinite() && s.omega_world.allFinite();
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// The accuracy pass: every grid state recorded (not timed).
bool record(ContactMethod& m, const ContactScenario& sc, double dt, long steps, Trajectory& tr,
            std::string& status) {
  m.reset(sc, dt);
  tr.dt_s = dt;
  tr.samples.clear();
  tr.asleep.clear();
  tr.samples.reserve(steps + 1);
  tr.asleep.reserve(steps + 1);
  tr.samples.push_back(m.sample());
  tr.asleep.push_back(m.asleep());
  for (long k = 1; k <= steps; ++k) {
    m.advance();
    const ContactSample s = m.sample();
    if (const std::string f = m.failure(); !f.empty()) {
      status = f + " at t = " + fmt("%.4g", k * dt) + " s";
      return false;
    }
    if (!finite(s)) {
      status = "diverged (non-finite state) at t = " + fmt("%.4g", k * dt) + " s";
      return false;
    }
    tr.samples.push_back(s);
    tr.asleep.push_back(m.asleep());
  }
  return true;
}

double time_once(ContactMethod& m, const ContactScenario& sc, double dt, long steps) {
  m.reset(sc, dt);  // not timed: building the world, loading the model
  const auto t0 = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k) m.advance();
  const auto t1 = std::chrono::steady_clock::now();
  // Read the result so no step can be skipped.
  volatile double sink = m.sample().position_world.z();
  (void)sink;
  return std::chrono::duration<double>(t1 - t0).count();
}

void write_trace(const std::string& dir, const Trajectory& tr) {
  std::FILE* f = std::fopen((dir + "/contact_trace.csv").c_str(), "w");
  if (!f) return;
  std::fprintf(f, "t,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz,asleep\n");
  for (size_t k = 0; k < tr.samples.size(); ++k) {
    const ContactSample& s = tr.samples[k];
    std::fprintf(
        f, "%.9g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d\n",
        k * tr.dt_s, s.position_world.x(), s.position_world.y(), s.position_world.z(),
        s.orientation.w(), s.orientation.x(), s.orientation.y(), s.orientation.z(),
        s.velocity_world.x(), s.velocity_world.y(), s.velocity_world.z(), s.omega_world.x(),
        s.omega_world.y(), s.omega_world.z(), tr.asleep[k]);
  }
  std::fclose(f);
}

// The harness measuring an exact method: the closed form sampled on the grid must come out
// exact (the goals of ours are stated against these same metrics). Then ours, measured by the
// same metrics on the same drops: its goals (the closed form's numbers, its rest event at the
// closed-form time, no work while it rests).
int self_check(const Options& o) {
  std::vector<std::unique_ptr<ContactMethod>> exact;
  exact.push_back(make_closed_form_drop());
  exact.push_back(make_ours_contact());
  int failures = 0;
  for (const auto& method : exact) {
    for (const ContactScenario& sc : make_contact_scenarios()) {
      if (!sc.drop) continue;
      const LensHull hull = make_lens_hull(sc.stone);
      for (const Step& st : make_steps(o.finest_exponent)) {
        Trajectory tr;
        std::string status;
        const long steps = std::lround(sc.duration_s / st.dt);
        try {
          if (!record(*method, sc, st.dt, steps, tr, status)) throw std::runtime_error(status);
        } catch (const std::exception& e) {
          std::fprintf(stderr, "self-check %s %s %s: FAILED: %s\n", method->name().c_str(),
                       sc.name.c_str(), st.label.c_str(), e.what());
          ++failures;
          continue;
        }
        const RunMetrics m = measure_run(sc, hull, true, tr);
        const double rest_error =
            std::abs(m.sleep_time_s - m.rest_reference_cutoff_s);  // within one step
        bool ok = !(m.apex_rel_error_max > 1e-9) && !(m.impact_error_max_s > 1e-12) &&
                  m.energy_gain_steps == 0 && m.penetration_max_m == 0.0 &&
                  m.jitter_position_m == 0.0 && rest_error <= st.dt;
        std::string extra;
        if (method->name() == "ours") {
          const ContactCounters c = method->counters();
          const double event_error = std::abs(c.rest_event_time_s - m.rest_reference_cutoff_s);
          ok = ok && event_error <= 1e-12 && c.work_while_asleep == 0 &&
               c.impacts == m.bounces_reference + 1;
          extra = "  rest event " + fmt("%.2e", event_error) + " s off, impacts " +
                  std::to_string(c.impacts) + ", work asleep " +
                  std::to_string(c.work_while_asleep);
        }
        if (!ok) ++failures;
        std::fprintf(stderr,
                     "self-check %-11s %-8s dt %-8s apex %-9s impact %-9s s  bounces %2d of %2d  "
                     "gains %ld  penetration %g  asleep %.6f s (closed form %.6f s)%s  %s\n",
                     method->name().c_str(), sc.name.c_str(), st.label.c_str(),
                     fmt("%.2e", m.apex_rel_error_max).c_str(),
                     fmt("%.2e", m.impact_error_max_s).c_str(), m.bounces_detected,
                     m.bounces_reference, m.energy_gain_steps, m.penetration_max_m, m.sleep_time_s,
                     m.rest_reference_cutoff_s, extra.c_str(), ok ? "ok" : "FAILED");
      }
    }
  }
  std::fprintf(stderr, "self-check: %s\n",
               failures == 0 ? "the closed form measures exact, and so does ours" : "FAILED");
  return failures == 0 ? 0 : 1;
}

void print_usage() {
  std::printf(
      "usage: contact_benchmark [--out DIR] [--scenario NAME]... [--method NAME]...\n"
      "                         [--finest K] [--quick] [--budget SECONDS] [--min-reps N]\n"
      "Runs ours (ours) and the peers (bullet_defaults, bullet_tuned, ode_defaults, ode_tuned,\n"
      "mujoco_defaults, mujoco_tuned) on the scenarios drop_e05, drop_e08, toss, slide,\n"
      "slide_frozen, rest, edge for dt = 1/30, 1/60 and 2^-5 .. 2^-K s; writes\n"
      "contact_results.csv, contact_bounces.csv, contact_tables.md, contact_settings.md,\n"
      "contact_goals.md, contact_headline.md, contact_notes.md and contact_*.dat into DIR\n"
      "(default .).\n"
      "  --finest K        smallest step 2^-K s (default 16)\n"
      "  --quick           --finest 10, --budget 0.02, --min-reps 1 (a smoke run)\n"
      "  --budget S        timed seconds per scenario, method and dt (default 0.2)\n"
      "  --min-reps N      repetitions at least (default 3; at most 21)\n"
      "  --self-check      measure the flat drop's closed form itself (sampled on the grid\n"
      "                    behind the method interface), then ours, at every dt and fail\n"
      "                    unless the metrics find both exact (apex 1e-9, impact 1e-12 s, no\n"
      "                    energy gain, no penetration, asleep within one step of the rest\n"
      "                    time; ours also: rest event within 1e-12 s of it, one impact per\n"
      "                    bounce plus the last, no work while asleep); writes nothing\n"
      "  --trace S,M,DT    also write run (scenario S, method M, dt label DT, e.g.\n"
      "                    drop_e05,bullet_tuned,1/60) state by state to DIR/contact_trace.csv\n");
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "contact_benchmark: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    try {
      if (a == "-h" || a == "--help") {
        print_usage();
        return 0;
      } else if (a == "--out") {
        o.out = value();
      } else if (a == "--scenario") {
        o.scenarios.push_back(value());
      } else if (a == "--method") {
        o.methods.push_back(value());
      } else if (a == "--finest") {
        o.finest_exponent = std::stoi(value());
        if (o.finest_exponent < 5 || o.finest_exponent > 20)
          throw std::invalid_argument("--finest must be 5 .. 20");
      } else if (a == "--quick") {
        o.finest_exponent = 10;
        o.budget_seconds = 0.02;
        o.min_reps = 1;
      } else if (a == "--budget") {
        o.budget_seconds = std::stod(value());
        if (!(o.budget_seconds >= 0.0 && o.budget_seconds <= 100.0))
          throw std::invalid_argument("--budget must be 0 .. 100 s");
      } else if (a == "--self-check") {
        o.self_check = true;
      } else if (a == "--trace") {
        o.trace = value();
      } else if (a == "--min-reps") {
        o.min_reps = std::stoi(value());
        if (o.min_reps < 1 || o.min_reps > o.max_reps)
          throw std::invalid_argument("--min-reps must be 1 .. 21");
      } else {
        std::fprintf(stderr, "contact_benchmark: unknown option %s (see --help)\n", a.c_str());
        return 2;
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "contact_benchmark: bad value for %s: %s\n", a.c_str(), e.what());
      return 2;
    }
  }

  if (o.self_check) return self_check(o);
  if (!vg_bench::make_output_folder("contact_benchmark", o.out)) return 1;
  init_contact_peers();
  std::vector<std::unique_ptr<ContactMethod>> all;
  all.push_back(make_ours_contact());
  for (bool tuned : {false, true}) all.push_back(make_bullet_contact(tuned));
  for (bool tuned : {false, true}) all.push_back(make_ode_contact(tuned));
  for (bool tuned : {false, true}) all.push_back(make_mujoco_contact(tuned));
  std::vector<std::unique_ptr<ContactMethod>> methods;
  for (auto& m : all) {
    if (o.methods.empty() || std::count(o.methods.begin(), o.methods.end(), m->name()))
      methods.push_back(std::move(m));
  }
  std::vector<ContactScenario> scenarios;
  for (const ContactScenario& s : make_contact_scenarios()) {
    if (o.scenarios.empty() || std::count(o.scenarios.begin(), o.scenarios.end(), s.name))
      scenarios.push_back(s);
  }
  if (methods.empty() || scenarios.empty()) {
    std::fprintf(stderr, "contact_benchmark: no such method or scenario (see --help)\n");
    return 2;
  }
  const std::vector<Step> steps = make_steps(o.finest_exponent);

  ReportInput report;
  report.scenarios = scenarios;
  report.plot_dt_labels = {"1/60", "1/1024"};
  for (const auto& m : methods)
    report.methods.push_back({m->name(), m->family(), m->variant(), m->version(), {}});

  const auto start = std::chrono::steady_clock::now();
  for (const ContactScenario& sc : scenarios) {
    const LensHull hull = make_lens_hull(sc.stone);
    for (size_t mi = 0; mi < methods.size(); ++mi) {
      ContactMethod& m = *methods[mi];
      for (const Step& st : steps) {
        ContactResult r;
        r.scenario = sc.name;
        r.method = m.name();
        r.family = m.family();
        r.variant = m.variant();
        r.peer = m.is_peer();
        r.dt = st.dt;
        r.dt_label = st.label;
        r.steps = std::lround(sc.duration_s / st.dt);
        try {
          Trajectory tr;
          const auto a0 = std::chrono::steady_clock::now();
          if (record(m, sc, st.dt, r.steps, tr, r.status)) {
            const double pass_s =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - a0).count();
            r.counters = m.counters();
            // Settings as run in the flat drop at 60 Hz (some depend on dt and the scenario).
            if (report.methods[mi].settings.empty() ||
                (sc.name == "drop_e05" && st.label == "1/60"))
              report.methods[mi].settings = m.settings();
            r.metrics = measure_run(sc, hull, !m.is_peer(), tr);
            if (o.trace == sc.name + "," + m.name() + "," + st.label) write_trace(o.out, tr);
            const bool plot =
                (sc.name == "drop_e05" || sc.name == "rest" || sc.name == "drop_e08") &&
                std::count(report.plot_dt_labels.begin(), report.plot_dt_labels.end(), st.label);
            if (plot) {
              PlotSeries ps{sc.name, m.name(), st.label, {}};
              const long stride = std::max(1L, static_cast<long>(tr.samples.size()) / 4000);
              for (size_t k = 0; k < tr.samples.size(); k += stride)
                ps.points.emplace_back(k * st.dt,
                                       tr.samples[k].position_world.z() - sc.stone.half_height_m);
              report.series.push_back(std::move(ps));
            }
            tr = Trajectory();  // free the samples before timing
            // Timing: whole scenario runs from reset, median of the repetitions.
            const int reps = static_cast<int>(std::clamp(o.budget_seconds / std::max(pass_s, 1e-6),
                                                         static_cast<double>(o.min_reps),
                                                         static_cast<double>(o.max_reps)));
            std::vector<double> runs;
            for (int k = 0; k < reps; ++k) runs.push_back(time_once(m, sc, st.dt, r.steps));
            std::sort(runs.begin(), runs.end());
            const size_t n = runs.size();
            r.run_s = n % 2 ? runs[n / 2] : 0.5 * (runs[n / 2 - 1] + runs[n / 2]);
            r.repetitions = reps;
            r.ns_per_step = r.run_s * 1e9 / r.steps;
            r.ns_per_step_min = runs.front() * 1e9 / r.steps;
            r.ns_per_sim_s = r.run_s * 1e9 / sc.duration_s;
          }
        } catch (const ContactNotRun& e) {
          r.status = e.what();
          if (report.methods[mi].settings.empty()) report.methods[mi].settings = m.settings();
        } catch (const std::exception& e) {
          r.status = std::string("failed: ") + e.what();
        }
        std::fprintf(
            stderr, "%-12s %-16s dt %-8s %-30s apex %-9s pen %-9s gains %5ld %9.1f ns/step\n",
            sc.name.c_str(), r.method.c_str(), st.label.c_str(), r.status.substr(0, 30).c_str(),
            fmt("%.2e", r.metrics.apex_rel_error_max).c_str(),
            fmt("%.2e", r.metrics.penetration_rest_m).c_str(), r.metrics.energy_gain_steps,
            r.ns_per_step);
        const bool not_run = r.status.rfind("not run", 0) == 0;
        report.results.push_back(r);
        if (not_run) {
          // A method that cannot run a scenario cannot run it at any dt: one row per dt anyway,
          // without trying again.
          for (const Step& rest : steps) {
            if (rest.dt >= st.dt) continue;
            ContactResult copy = r;
            copy.dt = rest.dt;
            copy.dt_label = rest.label;
            copy.steps = std::lround(sc.duration_s / rest.dt);
            report.results.push_back(copy);
          }
          break;
        }
      }
    }
  }
  report.elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report.timing_note =
      "Timing: each (scenario, method, dt) is one untimed recording pass (every grid "
      "state kept for the metrics), then whole-scenario runs from reset() (untimed) "
      "through the last grid time, repeated to fill about " +
      fmt("%.3g", o.budget_seconds) + " s (at least " + std::to_string(o.min_reps) + ", at most " +
      std::to_string(o.max_reps) +
      "); the median run time is reported per simulated second and per step. Whole run: " +
      fmt("%.0f", report.elapsed_s) + " s.";
  write_contact_outputs(o.out, report);
  methods.clear();  // ODE worlds before dCloseODE
  shutdown_contact_peers();
  std::fprintf(stderr, "contact_benchmark: %zu results in %.0f s, written to %s\n",
               report.results.size(), report.elapsed_s, o.out.c_str());
  return 0;
}
