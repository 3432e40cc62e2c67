// Results of the contact benchmark and the files written from them.
#pragma once

#include <string>
#include <vector>

#include "contact_method.h"
#include "trajectory_metrics.h"

namespace vg_bench {

struct ContactResult {
  std::string scenario, method, family, variant, dt_label, status = "ok";
  double dt = 0.0;
  long steps = 0;
  bool peer = true;
  RunMetrics metrics;
  ContactCounters counters;
  double ns_per_step = NAN, ns_per_step_min = NAN, ns_per_sim_s = NAN, run_s = NAN;
  int repetitions = 0;
  bool ok() const { return status == "ok"; }
};

// A time series for the plots: (t, height of the centre minus c) per method.
struct PlotSeries {
  std::string scenario, method, dt_label;
  std::vector<std::pair<double, double>> points;
};

struct MethodInfo {
  std::string name, family, variant, version;
  std::vector<Setting> settings;  // as run in the first scenario that ran
};

struct ReportInput {
  std::vector<ContactScenario> scenarios;
  std::vector<ContactResult> results;
  std::vector<PlotSeries> series;
  std::vector<MethodInfo> methods;
  std::vector<std::string> plot_dt_labels;
  double elapsed_s = 0.0;
  std::string timing_note;
};

void write_contact_outputs(const std::string& dir, const ReportInput& in);

}  // namespace vg_bench
