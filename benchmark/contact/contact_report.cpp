#include "contact_report.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "settings_format.h"

namespace vg_bench {
namespace {

std::string f(const char* format, double v) {
  if (std::isnan(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}
std::string sci(double v) {
  if (std::isnan(v)) return "-";
  if (v == 0.0) return "0";
  if (std::isinf(v)) return "inf";
  return f("%.2e", v);
}
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char ch : text) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}
std::string csv(double v) { return std::isnan(v) ? std::string() : f("%.9g", v); }
double deg(double rad) { return rad * 180.0 / M_PI; }

std::string file_label(const std::string& dt_label) {
  std::string s = dt_label;
  std::replace(s.begin(), s.end(), '/', '_');
  return s;
}

const ContactResult* find(const std::vector<ContactResult>& rs, const std::string& scenario,
                          const std::string& method, const std::string& dt_label) {
  for (const ContactResult& r : rs)
    if (r.scenario == scenario && r.method == method && r.dt_label == dt_label) return &r;
  return nullptr;
}

void write_csv(const std::string& dir, const ReportInput& in) {
  std::ofstream c(dir + "/contact_results.csv");
  c << "scenario,method,family,variant,dt_label,dt_s,steps,status,bounces_reference,"
       "bounces_detected,apex_rel_err_max,impact_err_max_s,rest_ref_s,rest_ref_cutoff_s,"
       "settle_time_s,sleep_time_s,energy_gain_steps,energy_rise_max_m,penetration_max_m,"
       "penetration_rest_m,jitter_position_m,jitter_rotation_rad,jitter_height_m,final_x_m,"
       "final_y_m,final_z_m,final_gap_m,final_tilt_deg,max_tilt_deg,slip_end_s,"
       "slip_distance_m,slip_max_pitch_deg,slide_final_m,events,impacts,rhs_evaluations,"
       "contact_steps,fallback_steps,work_while_asleep,rest_event_s,ns_per_event,ns_per_step_"
       "median,ns_per_step_min,ns_per_sim_s,repetitions\n";
  for (const ContactResult& r : in.results) {
    const RunMetrics& m = r.metrics;
    const bool ok = r.ok();
    auto v = [&](double x) { return ok ? csv(x) : std::string(); };
    const double per_event =
        r.counters.events > 0 ? r.run_s * 1e9 / static_cast<double>(r.counters.events) : NAN;
    c << r.scenario << "," << r.method << "," << r.family << "," << r.variant << "," << r.dt_label
      << "," << num17(r.dt) << "," << r.steps << "," << quoted(r.status) << ","
      << (ok ? std::to_string(m.bounces_reference) : "") << ","
      << (ok ? std::to_string(m.bounces_detected) : "") << "," << v(m.apex_rel_error_max) << ","
      << v(m.impact_error_max_s) << "," << v(m.rest_reference_s) << ","
      << v(m.rest_reference_cutoff_s) << "," << v(m.settle_time_s) << "," << v(m.sleep_time_s)
      << "," << (ok ? std::to_string(m.energy_gain_steps) : "") << "," << v(m.energy_rise_max_m)
      << "," << v(m.penetration_max_m) << "," << v(m.penetration_rest_m) << ","
      << v(m.jitter_position_m) << "," << v(m.jitter_rotation_rad) << "," << v(m.jitter_height_m)
      << "," << v(m.final_position.x()) << "," << v(m.final_position.y()) << ","
      << v(m.final_position.z()) << "," << v(m.final_gap_m) << "," << v(deg(m.final_tilt_rad))
      << "," << v(deg(m.max_tilt_rad)) << "," << v(m.slip_end_s) << "," << v(m.slip_distance_m)
      << "," << v(deg(m.slip_max_pitch_rad)) << "," << v(m.slide_final_m) << ","
      << (r.counters.events >= 0 ? std::to_string(r.counters.events) : "") << ","
      << (r.counters.impacts >= 0 ? std::to_string(r.counters.impacts) : "") << ","
      << (r.counters.rhs_evaluations >= 0 ? std::to_string(r.counters.rhs_evaluations) : "") << ","
      << (r.counters.contact_steps >= 0 ? std::to_string(r.counters.contact_steps) : "") << ","
      << (r.counters.fallback_steps >= 0 ? std::to_string(r.counters.fallback_steps) : "") << ","
      << (r.counters.work_while_asleep >= 0 ? std::to_string(r.counters.work_while_asleep) : "")
      << "," << csv(r.counters.rest_event_time_s) << "," << csv(per_event) << ","
      << csv(r.ns_per_step) << "," << csv(r.ns_per_step_min) << "," << csv(r.ns_per_sim_s) << ","
      << r.repetitions << "\n";
  }
  std::ofstream b(dir + "/contact_bounces.csv");
  b << "scenario,method,dt_label,dt_s,bounce,resolvable,apex_ref_m,apex_m,apex_rel_err,"
       "impact_ref_s,impact_s,impact_err_s\n";
  for (const ContactResult& r : in.results) {
    if (!r.ok()) continue;
    for (const BounceMetrics& bm : r.metrics.bounces) {
      b << r.scenario << "," << r.method << "," << r.dt_label << "," << num17(r.dt) << ","
        << bm.bounce << "," << (bm.resolvable ? 1 : 0) << "," << csv(bm.apex_reference_m) << ","
        << csv(bm.apex_measured_m) << ","
        << csv(std::abs(bm.apex_measured_m - bm.apex_reference_m) / bm.apex_reference_m) << ","
        << csv(bm.impact_reference_s) << "," << csv(bm.impact_measured_s) << ","
        << csv(std::abs(bm.impact_measured_s - bm.impact_reference_s)) << "\n";
    }
  }
}

std::string cost_cells(const ContactResult& r) {
  return f("%.3g", r.ns_per_sim_s / 1e3) + " | " + f("%.0f", r.ns_per_step);
}

std::string gains_cell(const RunMetrics& m) {
  return std::to_string(m.energy_gain_steps) + " / " + sci(m.energy_rise_max_m);
}

std::string where(const ContactScenario& sc, const RunMetrics& m) {
  if (m.final_position.z() < sc.board.top_z_m() - 0.5 * sc.board.thickness_m) return "table";
  return "board";
}

enum class Kind { drop, slide, rest, other };
Kind kind_of(const ContactScenario& sc) {
  if (sc.drop) return Kind::drop;
  if (sc.slide) return Kind::slide;
  if (sc.name == "rest") return Kind::rest;
  return Kind::other;
}

std::string header(Kind k) {
  switch (k) {
    case Kind::drop:
      return "| method | dt (s) | bounces seen | apex error (max rel., bounces 1-3) | impact "
             "time error (s) | settled (s) | asleep (s) | energy gains: steps / largest (m) | "
             "max penetration (m) | penetration, last 1 s (m) | jitter, last 1 s: position (m) "
             "/ rotation (rad) | us / simulated s | ns / step |\n"
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    case Kind::slide:
      return "| method | dt (s) | slip ends (s) | moved until then (mm) | largest pitch (deg) | "
             "moved by the end (mm) | energy gains: steps / largest (m) | max penetration (m) "
             "| penetration, last 1 s (m) | us / simulated s | ns / step |\n"
             "|---|---|---|---|---|---|---|---|---|---|---|\n";
    case Kind::rest:
      return "| method | dt (s) | penetration, last 1 s (m) | max penetration (m) | drift "
             "over 10 s (m) | jitter, last 1 s: position (m) / rotation (rad) / height (m) | "
             "energy gains: steps / largest (m) | asleep (s) | us / simulated s | ns / step |\n"
             "|---|---|---|---|---|---|---|---|---|---|\n";
    case Kind::other:
      return "| method | dt (s) | settled (s) | asleep (s) | rests on | gap (m) / tilt (deg) | "
             "energy gains: steps / largest (m) | max penetration (m) | penetration, last 1 s "
             "(m) | jitter, last 1 s: position (m) / rotation (rad) | us / simulated s | ns / "
             "step |\n"
             "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  }
  return "";
}

std::string row(const ContactScenario& sc, Kind k, const ContactResult& r) {
  std::ostringstream o;
  o << "| " << r.method << " | " << r.dt_label << " | ";
  const int cols = k == Kind::drop ? 11 : k == Kind::slide ? 9 : k == Kind::rest ? 8 : 10;
  if (!r.ok()) {
    o << r.status;
    for (int i = 1; i < cols; ++i) o << " |";
    o << " |\n";
    return o.str();
  }
  const RunMetrics& m = r.metrics;
  switch (k) {
    case Kind::drop:
      o << m.bounces_detected << " of " << m.bounces_reference << " | " << sci(m.apex_rel_error_max)
        << " | " << sci(m.impact_error_max_s) << " | " << f("%.4f", m.settle_time_s) << " | "
        << f("%.3f", m.sleep_time_s) << " | " << gains_cell(m) << " | " << sci(m.penetration_max_m)
        << " | " << sci(m.penetration_rest_m) << " | " << sci(m.jitter_position_m) << " / "
        << sci(m.jitter_rotation_rad) << " | " << cost_cells(r) << " |\n";
      break;
    case Kind::slide:
      o << f("%.5f", m.slip_end_s) << " | " << f("%.4f", m.slip_distance_m * 1e3) << " | "
        << f("%.2f", deg(m.slip_max_pitch_rad)) << " | " << f("%.4f", m.slide_final_m * 1e3)
        << " | " << gains_cell(m) << " | " << sci(m.penetration_max_m) << " | "
        << sci(m.penetration_rest_m) << " | " << cost_cells(r) << " |\n";
      break;
    case Kind::rest:
      o << sci(m.penetration_rest_m) << " | " << sci(m.penetration_max_m) << " | "
        << sci((m.final_position - sc.initial.position_world).norm()) << " | "
        << sci(m.jitter_position_m) << " / " << sci(m.jitter_rotation_rad) << " / "
        << sci(m.jitter_height_m) << " | " << gains_cell(m) << " | " << f("%.3f", m.sleep_time_s)
        << " | " << cost_cells(r) << " |\n";
      break;
    case Kind::other:
      o << f("%.4f", m.settle_time_s) << " | " << f("%.3f", m.sleep_time_s) << " | " << where(sc, m)
        << " | " << sci(m.final_gap_m) << " / " << f("%.2f", deg(m.final_tilt_rad)) << " | "
        << gains_cell(m) << " | " << sci(m.penetration_max_m) << " | " << sci(m.penetration_rest_m)
        << " | " << sci(m.jitter_position_m) << " / " << sci(m.jitter_rotation_rad) << " | "
        << cost_cells(r) << " |\n";
      break;
  }
  return o.str();
}

std::string reference_line(const ContactScenario& sc) {
  std::ostringstream o;
  if (sc.drop) {
    const FlatDropReference& d = *sc.drop;
    o << "Closed form: fall " << f("%.3f", d.fall_time_s() * 1e3) << " ms; apex heights "
      << f("%.4g", d.apex_height_m(1) * 1e3) << ", " << f("%.4g", d.apex_height_m(2) * 1e3) << ", "
      << f("%.4g", d.apex_height_m(3) * 1e3) << " mm ...; impacts at "
      << f("%.3f", d.impact_time_s(1) * 1e3) << ", " << f("%.3f", d.impact_time_s(2) * 1e3) << ", "
      << f("%.3f", d.impact_time_s(3) * 1e3) << " ms ...; " << d.last_bounce_above(1e-6)
      << " bounces higher than 1 um; rest at " << f("%.3f", d.rest_time_s() * 1e3)
      << " ms (Zeno limit), " << f("%.3f", d.rest_time_with_cutoff_s(1e-6) * 1e3)
      << " ms with the 1 um cut-off (no rebound lower than 1 um).";
  } else if (sc.slide) {
    const SlideReference& s = *sc.slide;
    if (sc.rotation_frozen) {
      o << "Closed form (rotation frozen): stops after v0^2/(2 mu g) = "
        << f("%.6f", s.frozen_distance_m() * 1e3)
        << " mm in v0/(mu g) = " << f("%.4f", s.frozen_stop_time_s() * 1e3) << " ms.";
    } else {
      o << "Reference (free lens, pitch-plane equations integrated by the harness): the contact "
           "point stops slipping at "
        << f("%.3f", s.free_slip_end_s * 1e3) << " ms after the centre moved "
        << f("%.4f", s.free_distance_m * 1e3) << " mm, largest pitch "
        << f("%.2f", deg(s.free_max_pitch_rad))
        << " deg; then it rocks. With rotation frozen: " << f("%.6f", s.frozen_distance_m() * 1e3)
        << " mm in " << f("%.4f", s.frozen_stop_time_s() * 1e3) << " ms.";
    }
  } else if (sc.name == "rest") {
    o << "Exact: the stone stays where it is (penetration, drift and jitter 0, no energy "
         "change).";
  } else {
    o << "No closed form; the checks are physical (no energy gain, no penetration, a still "
         "stone at rest).";
  }
  return o.str();
}

void write_tables(const std::string& dir, const ReportInput& in) {
  std::ofstream t(dir + "/contact_tables.md");
  for (const ContactScenario& sc : in.scenarios) {
    const Kind k = kind_of(sc);
    t << "### " << sc.name << "\n\n"
      << sc.description << "; " << f("%.3g", sc.duration_s) << " s simulated. "
      << reference_line(sc) << "\n\n";
    for (const std::string label : {"1/60", "1/1024"}) {
      t << "At dt = " << label << " s:\n\n" << header(k);
      for (const ContactResult& r : in.results)
        if (r.scenario == sc.name && r.dt_label == label) t << row(sc, k, r);
      t << "\n";
    }
    if (k == Kind::drop) {
      t << "Per bounce at dt = 1/1024 s (relative apex error; impact time error in s; - : not "
           "seen):\n\n| method | apex 1 | apex 2 | apex 3 | apex 4 | apex 5 | impact 1 | impact "
           "2 | impact 3 |\n|---|---|---|---|---|---|---|---|---|\n";
      for (const ContactResult& r : in.results) {
        if (r.scenario != sc.name || r.dt_label != "1/1024" || !r.ok()) continue;
        t << "| " << r.method;
        for (int b = 0; b < 5; ++b) {
          const auto& bs = r.metrics.bounces;
          t << " | "
            << (b < static_cast<int>(bs.size())
                    ? sci(std::abs(bs[b].apex_measured_m - bs[b].apex_reference_m) /
                          bs[b].apex_reference_m)
                    : "-");
        }
        for (int b = 0; b < 3; ++b) {
          const auto& bs = r.metrics.bounces;
          t << " | "
            << (b < static_cast<int>(bs.size())
                    ? sci(std::abs(bs[b].impact_measured_s - bs[b].impact_reference_s))
                    : "-");
        }
        t << " |\n";
      }
      t << "\n";
    }
    t << "<details><summary>All step sizes (" << sc.name << ")</summary>\n\n" << header(k);
    for (const ContactResult& r : in.results)
      if (r.scenario == sc.name) t << row(sc, k, r);
    t << "\n</details>\n\n";
  }
}

void write_settings(const std::string& dir, const ReportInput& in) {
  std::ofstream s(dir + "/contact_settings.md");
  std::map<std::string, std::vector<const MethodInfo*>> by_family;
  std::vector<std::string> order;
  for (const MethodInfo& m : in.methods) {
    if (!by_family.count(m.family)) order.push_back(m.family);
    by_family[m.family].push_back(&m);
  }
  for (const std::string& fam : order) {
    const auto& ms = by_family[fam];
    s << "#### " << fam << " — " << ms.front()->version << "\n\n";
    if (ms.size() == 1) {
      s << "| setting | " << ms.front()->variant << " | documentation |\n|---|---|---|\n";
      for (const Setting& st : ms.front()->settings)
        s << "| " << st.name << " | " << st.value << " | " << st.documentation << " |\n";
      s << "\n";
      continue;
    }
    s << "| setting |";
    for (const MethodInfo* m : ms) s << " " << m->variant << " |";
    s << " documentation |\n|---|";
    for (size_t i = 0; i < ms.size(); ++i) s << "---|";
    s << "---|\n";
    for (size_t i = 0; i < ms.front()->settings.size(); ++i) {
      const Setting& first = ms.front()->settings[i];
      s << "| " << first.name << " |";
      for (const MethodInfo* m : ms) {
        std::string value = "-";
        for (const Setting& st : m->settings)
          if (st.name == first.name) value = st.value;
        s << " " << value << " |";
      }
      s << " " << first.documentation << " |\n";
    }
    s << "\n";
  }
}

void write_plots(const std::string& dir, const ReportInput& in) {
  std::vector<std::string> names;
  for (const MethodInfo& m : in.methods) names.push_back(m.name);
  for (const ContactScenario& sc : in.scenarios) {
    if (!sc.drop) continue;
    std::ofstream w(dir + "/contact_wp_" + sc.name + ".dat");
    // One block per method that has a point (gnuplot skips nothing gracefully).
    for (const std::string& m : names) {
      std::ostringstream block;
      for (const ContactResult& r : in.results) {
        if (r.scenario != sc.name || r.method != m || !r.ok() || std::isnan(r.ns_per_sim_s) ||
            std::isnan(r.metrics.apex_rel_error_max))
          continue;
        block << f("%.6g", std::max(r.metrics.apex_rel_error_max, 1e-17)) << " "
              << f("%.6g", r.ns_per_sim_s) << " " << r.dt_label << "\n";
      }
      if (!block.str().empty()) w << "\"" << m << "\"\n" << block.str() << "\n\n";
    }
  }
  // Height over time: one file with every method, and one per variant group (engine defaults;
  // tuned engines and ours), each led by the reference (closed form or exact rest).
  auto variant_of = [&](const std::string& method) {
    for (const MethodInfo& m : in.methods)
      if (m.name == method) return m.variant;
    return std::string();
  };
  for (const ContactScenario& sc : in.scenarios) {
    for (const std::string& label : in.plot_dt_labels) {
      bool any = false;
      for (const PlotSeries& p : in.series) any |= p.scenario == sc.name && p.dt_label == label;
      if (!any) continue;
      for (const std::string group : {"", "_defaults", "_tuned"}) {
        std::ofstream h(dir + "/contact_height_" + sc.name + "_" + file_label(label) + group +
                        ".dat");
        if (sc.drop) {
          h << "\"closed form\"\n";
          const int n = 4000;
          for (int k = 0; k <= n; ++k) {
            const double t = sc.duration_s * k / n;
            h << f("%.9g", t) << " " << f("%.9g", sc.drop->height_at(t)) << "\n";
          }
          h << "\n\n";
        } else {
          h << "\"exact\"\n0 0\n" << f("%.9g", sc.duration_s) << " 0\n\n\n";
        }
        for (const std::string& m : names) {
          const std::string v = variant_of(m);
          if (group == "_defaults" && v != "defaults") continue;
          if (group == "_tuned" && v == "defaults") continue;
          for (const PlotSeries& p : in.series) {
            if (p.scenario != sc.name || p.dt_label != label || p.method != m) continue;
            h << "\"" << m << "\"\n";
            for (const auto& [t, z] : p.points) h << f("%.9g", t) << " " << f("%.9g", z) << "\n";
            h << "\n\n";
          }
        }
      }
    }
  }
}

// The best (smallest) value of a metric over the step sizes of one method and scenario.
const ContactResult* best_over_dt(const std::vector<ContactResult>& rs, const std::string& scenario,
                                  const std::string& method, double RunMetrics::*field) {
  const ContactResult* best = nullptr;
  for (const ContactResult& r : rs) {
    if (r.scenario != scenario || r.method != method || !r.ok() || std::isnan(r.metrics.*field))
      continue;
    if (!best || r.metrics.*field < best->metrics.*field) best = &r;
  }
  return best;
}

// The goals on ours, each with the figure it is judged by, over every step size that ran.
void write_ours_goals(std::ofstream& g, const ReportInput& in) {
  auto ours_runs = [&](const std::string& scenario) {
    std::vector<const ContactResult*> rs;
    for (const ContactResult& r : in.results)
      if (r.method == "ours" && r.scenario == scenario) rs.push_back(&r);
    return rs;
  };
  auto verdict = [](bool met) { return met ? std::string("met") : std::string("MISSED"); };
  g << "| goal (ours) | measured, every dt that ran | verdict |\n|---|---|---|\n";
  for (const ContactScenario& sc : in.scenarios) {
    if (!sc.drop) continue;
    double apex = 0, impact = 0, rest_err = 0, rest_t = NAN;
    int failed = 0;
    bool all_bounces = true;
    for (const ContactResult* r : ours_runs(sc.name)) {
      if (!r->ok()) {
        ++failed;
        continue;
      }
      apex = std::max(apex, r->metrics.apex_rel_error_max);
      impact = std::max(impact, r->metrics.impact_error_max_s);
      // Every bounce whose flight spans 3 grid steps (the harness needs 3 samples to see a
      // flight), not only bounces 1-3, must be seen at e^(2n) h0.
      for (const BounceMetrics& b : r->metrics.bounces) {
        if (!b.resolvable) continue;
        all_bounces &= !std::isnan(b.apex_measured_m);
        if (!std::isnan(b.apex_measured_m))
          apex =
              std::max(apex, std::abs(b.apex_measured_m - b.apex_reference_m) / b.apex_reference_m);
      }
      rest_t = r->counters.rest_event_time_s;
      rest_err = std::max(rest_err, std::abs(rest_t - r->metrics.rest_reference_cutoff_s));
    }
    const double cut = sc.drop->rest_time_with_cutoff_s(1e-6);
    g << "| " << sc.name
      << ": apex heights e^(2n) h0 within 1e-9 relative (every bounce the grid resolves) | "
      << sci(apex) << (failed ? " (" + std::to_string(failed) + " runs failed)" : "")
      << (all_bounces ? ", every resolvable bounce seen" : ", resolvable bounces missing") << " | "
      << verdict(failed == 0 && apex <= 1e-9 && all_bounces) << " |\n";
    g << "| " << sc.name << ": impact times within 1e-12 s (impacts 1-3) | " << sci(impact)
      << " s | " << verdict(failed == 0 && impact <= 1e-12) << " |\n";
    g << "| " << sc.name << ": rest at the closed-form time (" << f("%.6f", cut * 1e3)
      << " ms with the 1 um cut-off; " << f("%.6f", sc.drop->rest_time_s() * 1e3)
      << " ms uncut) | rest event at " << f("%.6f", rest_t * 1e3) << " ms, largest error "
      << sci(rest_err) << " s | " << verdict(failed == 0 && rest_err <= 1e-12) << " |\n";
  }
  long gains = 0;
  double rise = 0.0, pen_max = 0.0;
  int failed = 0;
  for (const ContactResult& r : in.results) {
    if (r.method != "ours") continue;
    if (r.status.rfind("not run", 0) == 0) continue;
    if (!r.ok()) {
      ++failed;
      continue;
    }
    gains += r.metrics.energy_gain_steps;
    rise = std::max(rise, r.metrics.energy_rise_max_m);
    pen_max = std::max(pen_max, r.metrics.penetration_max_m);
  }
  g << "| no energy gain (steps whose energy rose by more than 0.1 nm of height), every scenario "
       "| "
    << gains << " steps; largest rise over the running minimum " << sci(rise)
    << " m of height (round-off); largest penetration anywhere " << sci(pen_max) << " m"
    << (failed ? "; " + std::to_string(failed) + " runs failed" : "") << " | "
    << verdict(gains == 0 && failed == 0) << " |\n";
  double pen = 0, jit = 0, drift = 0;
  long work = 0;
  bool slept = true;
  for (const ContactResult* r : ours_runs("rest")) {
    if (!r->ok()) {
      slept = false;
      continue;
    }
    pen = std::max(pen, r->metrics.penetration_max_m);
    jit = std::max({jit, r->metrics.jitter_position_m, r->metrics.jitter_rotation_rad});
    for (const ContactScenario& sc : in.scenarios)
      if (sc.name == "rest")
        drift = std::max(drift, (r->metrics.final_position - sc.initial.position_world).norm());
    if (r->counters.work_while_asleep < 0) slept = false;
    work = std::max(work, r->counters.work_while_asleep);
  }
  g << "| rest: zero penetration, drift and jitter | penetration " << sci(pen) << " m, drift "
    << sci(drift) << " m, jitter (position m, rotation rad) " << sci(jit) << " | "
    << verdict(pen == 0 && jit == 0 && drift == 0) << " |\n";
  const ContactResult* rest60 = find(in.results, "rest", "ours", "1/60");
  g << "| a resting stone costs ours nothing per step | integration and search work while "
       "asleep: "
    << work << " (flight steps, searches, contact steps and evaluations, fallback sub-steps)"
    << (rest60 && rest60->ok() ? "; what remains is the call: " + f("%.0f", rest60->ns_per_step) +
                                     " ns per advance_to at 1/60 s"
                               : "")
    << " | " << verdict(slept && work == 0) << " |\n";
  // Cost at the best peer's accuracy: the flat drops (the only scenarios with a closed form to
  // measure accuracy against).
  for (const ContactScenario& sc : in.scenarios) {
    if (!sc.drop) continue;
    const ContactResult* best_peer = nullptr;
    for (const ContactResult& r : in.results) {
      if (r.scenario != sc.name || !r.peer || !r.ok() || std::isnan(r.ns_per_sim_s) ||
          std::isnan(r.metrics.apex_rel_error_max))
        continue;
      const double e = r.metrics.apex_rel_error_max;
      if (!best_peer || e < best_peer->metrics.apex_rel_error_max ||
          (e == best_peer->metrics.apex_rel_error_max && r.ns_per_sim_s < best_peer->ns_per_sim_s))
        best_peer = &r;
    }
    const ContactResult* ours_cheapest = nullptr;
    for (const ContactResult* r : ours_runs(sc.name)) {
      if (!r->ok() || std::isnan(r->ns_per_sim_s)) continue;
      if (best_peer && !(r->metrics.apex_rel_error_max <= best_peer->metrics.apex_rel_error_max))
        continue;
      if (!ours_cheapest || r->ns_per_sim_s < ours_cheapest->ns_per_sim_s) ours_cheapest = r;
    }
    if (!best_peer || !ours_cheapest) continue;
    g << "| " << sc.name
      << ": cheaper per simulated second than every peer at the best peer's "
         "accuracy | best peer "
      << best_peer->method << " at dt " << best_peer->dt_label << ": apex error "
      << sci(best_peer->metrics.apex_rel_error_max) << " for "
      << f("%.3g", best_peer->ns_per_sim_s / 1e3) << " us / simulated s; ours (dt "
      << ours_cheapest->dt_label << ", apex error "
      << sci(ours_cheapest->metrics.apex_rel_error_max) << ") "
      << f("%.3g", ours_cheapest->ns_per_sim_s / 1e3)
      << " us: " << f("%.3g", best_peer->ns_per_sim_s / ours_cheapest->ns_per_sim_s)
      << "x cheaper | " << verdict(ours_cheapest->ns_per_sim_s < best_peer->ns_per_sim_s) << " |\n";
  }
  g << "\nOurs' work per scenario at dt = 1/60 s (an event: an impact, a change of contact mode, "
       "rest; the counts do not depend on dt):\n\n| scenario | events | impacts | plane-contact "
       "steps / right-hand sides | fallback sub-steps | us / simulated s | us / event | rest "
       "event (s) |\n|---|---|---|---|---|---|---|---|\n";
  for (const ContactScenario& sc : in.scenarios) {
    const ContactResult* r = find(in.results, sc.name, "ours", "1/60");
    if (!r || !r->ok()) {
      g << "| " << sc.name << " | " << (r ? r->status : std::string("-")) << " | | | | | | |\n";
      continue;
    }
    const ContactCounters& c = r->counters;
    g << "| " << sc.name << " | " << c.events << " | " << c.impacts << " | " << c.contact_steps
      << " / " << c.rhs_evaluations << " | " << c.fallback_steps << " | "
      << f("%.3g", r->ns_per_sim_s / 1e3) << " | "
      << (c.events > 0 ? f("%.3g", r->run_s * 1e6 / static_cast<double>(c.events)) : "-") << " | "
      << f("%.9f", c.rest_event_time_s) << " |\n";
  }
  // Issue 17: at the peers' own step, ours no dearer than the cheapest peer in every scenario,
  // and sustained contact 100x cheaper than before (65 / 19.5 / 12 ms per simulated second for
  // toss / slide / edge at 1/60 s, the run of the Dormand-Prince 5(4) plane contact).
  g << "\nAt dt = 1/60 s, every scenario (issue 17): ours against the cheapest peer configuration "
       "in the same run, and sustained contact against the cost before the DOP853 plane contact "
       "(toss 65, slide 19.5, edge 12 ms per simulated second):\n\n| scenario | ours (us / "
       "simulated s) | cheapest peer (us) | ours / cheapest | energy-gain steps | before / now "
       "| verdict |\n|---|---|---|---|---|---|---|\n";
  const std::pair<const char*, double> before_us[] = {
      {"toss", 65e3}, {"slide", 19.5e3}, {"edge", 12e3}};
  for (const ContactScenario& sc : in.scenarios) {
    const ContactResult* ours = find(in.results, sc.name, "ours", "1/60");
    const ContactResult* cheapest = nullptr;
    for (const MethodInfo& mi : in.methods) {
      if (mi.name == "ours") continue;
      const ContactResult* r = find(in.results, sc.name, mi.name, "1/60");
      if (!r || !r->ok() || std::isnan(r->ns_per_sim_s)) continue;
      if (!cheapest || r->ns_per_sim_s < cheapest->ns_per_sim_s) cheapest = r;
    }
    if (!ours || !ours->ok() || !cheapest) {
      g << "| " << sc.name << " | " << (ours ? ours->status : std::string("-")) << " | | | | | |\n";
      continue;
    }
    const double ratio = ours->ns_per_sim_s / cheapest->ns_per_sim_s;
    std::string reduction = "-";
    bool reduced = true;
    for (const auto& [name, us] : before_us) {
      if (sc.name != name) continue;
      const double factor = us * 1e3 / ours->ns_per_sim_s;
      reduction = f("%.3g", factor) + "x";
      reduced = factor >= 100.0;
    }
    g << "| " << sc.name << " | " << f("%.3g", ours->ns_per_sim_s / 1e3) << " | "
      << f("%.3g", cheapest->ns_per_sim_s / 1e3) << " (" << cheapest->method << ") | "
      << f("%.3g", ratio) << " | " << ours->metrics.energy_gain_steps << " | " << reduction << " | "
      << verdict(ratio <= 1.0 && reduced && ours->metrics.energy_gain_steps == 0) << " |\n";
  }
  for (const std::string label : {"1/60", "1/1024"}) {
    g << "\nCost per simulated second at dt = " << label
      << " s, every scenario (us; ours' cost hardly depends on dt, a peer's grows as 1/dt):\n\n"
         "| scenario |";
    for (const MethodInfo& mi : in.methods) g << " " << mi.name << " |";
    g << " ours / cheapest peer |\n|---|";
    for (size_t i = 0; i <= in.methods.size(); ++i) g << "---|";
    g << "\n";
    for (const ContactScenario& sc : in.scenarios) {
      g << "| " << sc.name << " |";
      double cheapest_peer = NAN, ours_cost = NAN;
      for (const MethodInfo& mi : in.methods) {
        const ContactResult* r = find(in.results, sc.name, mi.name, label);
        const bool ok = r && r->ok() && !std::isnan(r->ns_per_sim_s);
        g << " " << (ok ? f("%.3g", r->ns_per_sim_s / 1e3) : std::string("-")) << " |";
        if (!ok) continue;
        if (mi.name == "ours")
          ours_cost = r->ns_per_sim_s;
        else if (std::isnan(cheapest_peer) || r->ns_per_sim_s < cheapest_peer)
          cheapest_peer = r->ns_per_sim_s;
      }
      g << " " << f("%.3g", ours_cost / cheapest_peer) << " |\n";
    }
  }
  g << "\n";
}

void write_goals_and_headline(const std::string& dir, const ReportInput& in) {
  std::ofstream g(dir + "/contact_goals.md");
  std::ofstream h(dir + "/contact_headline.md");
  const ContactResult* ours = find(in.results, "drop_e05", "ours", "1/60");
  const bool ours_ran = ours && ours->ok();
  if (!ours_ran) {
    const std::string why = ours ? ours->status : "not in this run";
    g << "Ours (`ours`): " << why
      << " — the goals on ours (apex heights and impact times exact to 1e-9 relative and "
         "1e-12 s, zero energy gains, zero penetration and jitter at rest, rest at the "
         "closed-form time, cheaper per simulated second than every peer at the best peer's "
         "accuracy, a resting stone free) are not evaluated in this run.\n\n";
  } else {
    write_ours_goals(g, in);
  }
  // Peers: the resting stone's cost per step against the dropped stone's.
  g << "What a resting stone costs each peer per step, against a step of the flat drop (dt = "
       "1/60 s; a sleeping body is skipped by the integrator but still costs the step's "
       "collision and bookkeeping):\n\n| method | rest: ns / step | drop_e05: ns / step | rest / "
       "drop | asleep after (s) |\n|---|---|---|---|---|\n";
  for (const MethodInfo& mi : in.methods) {
    const ContactResult* rest = find(in.results, "rest", mi.name, "1/60");
    const ContactResult* drop = find(in.results, "drop_e05", mi.name, "1/60");
    if (!rest || !drop || !rest->ok() || !drop->ok()) {
      g << "| " << mi.name << " | " << (rest ? rest->status : "-") << " | | | |\n";
      continue;
    }
    g << "| " << mi.name << " | " << f("%.0f", rest->ns_per_step) << " | "
      << f("%.0f", drop->ns_per_step) << " | " << f("%.2f", rest->ns_per_step / drop->ns_per_step)
      << " | " << f("%.3f", rest->metrics.sleep_time_s) << " |\n";
  }

  // Headline: one line on ours, one table of every method.
  std::string ours_line = ours ? ours->status : "not in this run";
  if (ours_ran) {
    double apex = 0, impact = 0;
    for (const ContactResult& r : in.results) {
      if (r.method != "ours" || r.scenario != "drop_e05" || !r.ok()) continue;
      apex = std::max(apex, r.metrics.apex_rel_error_max);
      impact = std::max(impact, r.metrics.impact_error_max_s);
    }
    ours_line =
        "flat drop e 0.5 from 5 cm exact at every dt (apex error <= " + sci(apex) +
        ", impact time error <= " + sci(impact) + " s, rest event at " +
        f("%.6f", ours->counters.rest_event_time_s * 1e3) +
        " ms), no energy gain in any scenario, a resting stone frozen with no integration "
        "work; goals met and missed in [contact.md](docs/benchmarks/contact.md#goals-issue-11)";
  }
  h << "- Contact (size-33 slate stone on the real board; closed forms for the flat drop and "
       "the slide): ours — "
    << ours_line
    << ".\n- Every method, the peers each with its defaults and tuned for a 22 mm body "
       "([settings](docs/benchmarks/contact.md#settings-as-run)):\n\n"
    << "| method | drop e 0.5: apex error at 1/60 s | best apex error (dt; us per simulated "
       "s) | bounces seen at 1/1024 s (closed form: 7) | rest at 1/60 s: sinking / drift in 10 s "
       "/ jitter in the last 1 s | energy gains (steps, all scenarios at 1/60 s) | us per "
       "simulated s, drop / rest at 1/60 s |\n"
       "|---|---|---|---|---|---|---|\n";
  Eigen::Vector3d rest_start = Eigen::Vector3d::Constant(NAN);
  for (const ContactScenario& sc : in.scenarios)
    if (sc.name == "rest") rest_start = sc.initial.position_world;
  for (const MethodInfo& mi : in.methods) {
    const ContactResult* d60 = find(in.results, "drop_e05", mi.name, "1/60");
    if (!d60 || !d60->ok()) {
      h << "| " << mi.name << " | " << (d60 ? d60->status : "not run") << " | | | | | |\n";
      continue;
    }
    const ContactResult* best =
        best_over_dt(in.results, "drop_e05", mi.name, &RunMetrics::apex_rel_error_max);
    const ContactResult* d1024 = find(in.results, "drop_e05", mi.name, "1/1024");
    const ContactResult* rest = find(in.results, "rest", mi.name, "1/60");
    long gains = 0;
    for (const ContactResult& r : in.results)
      if (r.method == mi.name && r.dt_label == "1/60" && r.ok())
        gains += r.metrics.energy_gain_steps;
    h << "| " << mi.name << " | " << sci(d60->metrics.apex_rel_error_max) << " | "
      << (best ? sci(best->metrics.apex_rel_error_max) + " (" + best->dt_label + "; " +
                     f("%.3g", best->ns_per_sim_s / 1e3) + ")"
               : "-")
      << " | " << (d1024 && d1024->ok() ? std::to_string(d1024->metrics.bounces_detected) : "-")
      << " | "
      << (rest && rest->ok() ? sci(rest->metrics.penetration_rest_m) + " m / " +
                                   sci((rest->metrics.final_position - rest_start).norm()) +
                                   " m / " + sci(rest->metrics.jitter_position_m) + " m"
                             : "-")
      << " | " << gains << " | " << f("%.3g", d60->ns_per_sim_s / 1e3) << " / "
      << (rest && rest->ok() ? f("%.3g", rest->ns_per_sim_s / 1e3) : "-") << " |\n";
  }
}

}  // namespace

void write_contact_outputs(const std::string& dir, const ReportInput& in) {
  write_csv(dir, in);
  write_tables(dir, in);
  write_settings(dir, in);
  write_plots(dir, in);
  write_goals_and_headline(dir, in);
  std::ofstream n(dir + "/contact_notes.md");
  n << "- " << in.timing_note << "\n";
  for (const ContactScenario& sc : in.scenarios) {
    if (sc.slide && !sc.rotation_frozen) {
      n << "- Free-lens slide reference computed by the harness: slip ends at "
        << f("%.6f", sc.slide->free_slip_end_s * 1e3) << " ms, centre moved "
        << f("%.6f", sc.slide->free_distance_m * 1e3) << " mm, largest pitch "
        << f("%.3f", deg(sc.slide->free_max_pitch_rad)) << " deg.\n";
    }
  }
}

}  // namespace vg_bench
