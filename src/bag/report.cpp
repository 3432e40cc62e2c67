#include "virtual_go/bag/report.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "virtual_go/common/formatting.h"
#include "virtual_go/common/sim_time.h"
#include "virtual_go/common/validation.h"

namespace virtual_go {
namespace bag {
namespace {

std::string fixed(double v, int digits) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << v;
  return out.str();
}

std::string sci(double v) {
  if (std::isnan(v)) return "n/a";
  std::ostringstream out;
  out << std::scientific << std::setprecision(2) << v;
  return out.str();
}

// Microseconds are enough for a report line.
std::string short_stamp_text(std::int64_t ns) { return fixed(to_seconds(ns), 6); }

std::string vector_text(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out << std::setprecision(6) << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return out.str();
}

// A figure listing of stamp events, the first few only: a broken topic can have thousands.
void print_stamp_events(std::ostream& out, const std::string& topic, const char* what,
                        const std::vector<StampEvent>& events) {
  constexpr std::size_t kShown = 5;
  for (std::size_t i = 0; i < events.size() && i < kShown; ++i) {
    out << "  " << what << " " << topic << " at " << short_stamp_text(events[i].stamp_ns)
        << " s (step " << fixed(to_seconds(events[i].step_ns) * 1e3, 3) << " ms, message "
        << events[i].index << ")\n";
  }
  if (events.size() > kShown) {
    out << "  ... " << events.size() - kShown << " more " << what << " on " << topic << "\n";
  }
}

// One row per stone of ~stones: its segments and the worst of each figure over them.
void print_stones(std::ostream& out, const Report& report) {
  out << "\nstones (" << report.recording.stones_topic << " and /tf, events from "
      << (report.recording.events_topic.empty() ? "nowhere" : report.recording.events_topic)
      << "), worst over each stone's segments:\n";
  out << "  " << std::left << std::setw(14) << "stone" << std::setw(7) << "color" << std::right
      << std::setw(6) << "segs" << std::setw(8) << "samples" << std::setw(8) << "flights"
      << std::setw(11) << "orient rad" << std::setw(11) << "pos m" << std::setw(11) << "energy"
      << std::setw(11) << "E rise" << std::setw(11) << "gap m" << std::setw(8) << "rest mv"
      << "\n";
  for (const StonePhysics& stone : report.stones) {
    out << "  " << std::left << std::setw(14) << cut_user_text(stone.name, 13) << std::setw(7)
        << cut_user_text(stone.color, 6) << std::right;
    if (!stone.physics) {
      out << "  " << stone.note << "\n";
      continue;
    }
    std::size_t samples = 0, flights = 0, moved = 0;
    double orient = 0.0, pos = 0.0, energy = 0.0, rise = 0.0, gap = INFINITY;
    bool predicted = false, board = false;
    for (const SegmentResult& s : stone.physics->segments) {
      samples += s.samples;
      moved += s.rest_moved;
      if (s.samples == 0) continue;
      if (s.kind == SegmentKind::flight) ++flights;
      if (s.predicted) predicted = true;
      if (s.predicted) orient = std::fmax(orient, s.max_orientation_error);
      if (s.predicted) pos = std::fmax(pos, s.max_position_error);
      if (s.kind != SegmentKind::contact) energy = std::fmax(energy, s.max_energy_drift);
      if (s.kind == SegmentKind::contact) rise = std::fmax(rise, s.max_energy_rise);
      if (s.board) gap = std::fmin(gap, s.min_gap_m);
      board = board || s.board;
    }
    out << std::setw(6) << stone.physics->segments.size() << std::setw(8) << samples << std::setw(8)
        << flights << std::setw(11) << (predicted ? sci(orient) : "n/a") << std::setw(11)
        << (predicted ? sci(pos) : "n/a") << std::setw(11) << sci(energy) << std::setw(11)
        << sci(rise) << std::setw(11) << (board ? sci(gap) : "-") << std::setw(8) << moved << "\n";
  }
}

}  // namespace

bool Report::checks_pass() const {
  return std::all_of(checks.begin(), checks.end(), [](const Check& c) { return c.pass; });
}

Report analyse(Recording recording, const LimitOverrides& limits) {
  Report r;
  r.recording = std::move(recording);
  r.problems = r.recording.problems;
  for (const TopicStamps& t : r.recording.topics) {
    r.stats.push_back(compute_stamp_statistics(t.stamps_ns));
  }
  const Recording& rec = r.recording;
  if (rec.info && (!rec.odom.empty() || !rec.stone_tracks.empty())) {
    // Only ~info itself is blamed on ~info; a bad event or sample affects its own segment
    // inside check_physics, and anything else that fails is named as what it is.
    bool info_ok = false;
    try {
      model_from_info(*rec.info);
      info_ok = true;
    } catch (const std::exception& e) {
      r.problems.push_back(std::string("~info cannot describe the motion: ") + e.what());
    }
    if (info_ok && !rec.odom.empty()) {
      try {
        r.physics = check_physics(*rec.info, rec.odom,
                                  events_of_stone(rec.events, rec.info->stone_frame, *rec.info));
      } catch (const std::exception& e) {
        r.problems.push_back(std::string("physics check failed: ") + e.what());
      }
    }
    for (const StoneTrack& track : rec.stone_tracks) {
      if (!info_ok) break;
      if (track.name == rec.info->stone_frame && !rec.odom.empty()) continue;  // ~odom's stone
      StonePhysics stone;
      stone.name = track.name;
      stone.color = track.color;
      try {
        stone.info = info_of_stone(*rec.info, track);
        stone.physics = check_physics(stone.info, track.samples,
                                      events_of_stone(rec.events, track.name, *rec.info));
      } catch (const std::exception& e) {
        stone.note = "stone " + cut_user_text(track.name) + " cannot be checked: " + e.what();
      }
      r.stones.push_back(std::move(stone));
    }
  }
  if (!rec.snapshots.empty()) r.overlap = check_stone_overlaps(rec.stone_tracks, rec.snapshots);
  // Islands: every checked stone with its ~stones track (the stone of ~odom too, checked on ~odom).
  std::vector<IslandStone> island_stones;
  auto track_of = [&](const std::string& name) -> const StoneTrack* {
    for (const StoneTrack& t : rec.stone_tracks) {
      if (t.name == name) return &t;
    }
    return nullptr;
  };
  if (r.physics) {
    island_stones.push_back(
        {rec.info->stone_frame, &*rec.info, &*r.physics, track_of(rec.info->stone_frame)});
  }
  for (StonePhysics& s : r.stones) {
    if (s.physics) island_stones.push_back({s.name, &s.info, &*s.physics, track_of(s.name)});
  }
  if (!island_stones.empty() && !rec.snapshots.empty()) {
    try {
      r.islands = check_stone_islands(island_stones, rec.events, rec.snapshots);
      exempt_island_samples(*r.islands, island_stones);
    } catch (const std::exception& e) {
      r.problems.push_back(std::string("island check failed: ") + e.what());
    }
  }
  r.checks = run_checks(r.recording, r.stats, r.physics ? &*r.physics : nullptr, limits, r.stones,
                        r.overlap ? &*r.overlap : nullptr, r.islands ? &*r.islands : nullptr);
  return r;
}

void print_report(std::ostream& out, const Report& report) {
  const Recording& rec = report.recording;
  out << "bag " << rec.path << ": " << rec.message_count << " messages over "
      << fixed(rec.bag_duration_s, 3) << " s (receipt time)\n";

  out << "\ntopics (periods from header stamps; * = receipt time, no header):\n";
  out << "  " << std::left << std::setw(34) << "topic" << std::right << std::setw(7) << "count"
      << std::setw(10) << "rate Hz" << std::setw(10) << "p50 ms" << std::setw(10) << "p99 ms"
      << std::setw(10) << "max ms" << std::setw(6) << "gaps" << std::setw(10) << "repeated"
      << std::setw(10) << "backwards"
      << "\n";
  for (std::size_t i = 0; i < rec.topics.size(); ++i) {
    const TopicStamps& t = rec.topics[i];
    const StampStatistics& s = report.stats[i];
    out << "  " << std::left << std::setw(34) << (t.topic + (t.header_stamps ? "" : " *"))
        << std::right << std::setw(7) << s.count;
    if (t.aperiodic) {
      out << std::setw(10) << "latched" << std::setw(30) << "" << std::setw(6) << "-";
    } else if (t.on_change) {
      out << std::setw(10) << "on move" << std::setw(30) << "" << std::setw(6) << "-";
    } else {
      out << std::setw(10) << fixed(s.mean_rate_hz, 2) << std::setw(10)
          << fixed(s.period_p50_s * 1e3, 3) << std::setw(10) << fixed(s.period_p99_s * 1e3, 3)
          << std::setw(10) << fixed(s.period_max_s * 1e3, 3) << std::setw(6) << s.gaps.size();
    }
    out << std::setw(10) << s.repeated.size() << std::setw(10) << s.non_increasing.size() << "\n";
  }
  for (std::size_t i = 0; i < rec.topics.size(); ++i) {
    if (rec.topics[i].aperiodic) continue;
    if (!rec.topics[i].on_change) {
      print_stamp_events(out, rec.topics[i].topic, "gap", report.stats[i].gaps);
    }
    print_stamp_events(out, rec.topics[i].topic, "repeated stamp", report.stats[i].repeated);
    print_stamp_events(out, rec.topics[i].topic, "backwards stamp", report.stats[i].non_increasing);
  }

  if (rec.info) {
    const RecordingInfo& i = *rec.info;
    out << "\nstone (" << i.topic << "): model " << i.model << ", integrator " << i.integrator
        << ", dt " << i.dt_s << " s, rate " << i.rate_hz << " Hz, mass " << i.mass
        << " kg, moments " << vector_text(i.principal_moments_body) << " kg m^2, gravity "
        << vector_text(i.gravity_world) << " m/s^2\n";
  }

  if (report.physics) {
    const PhysicsResult& p = *report.physics;
    out << "\nsegments ("
        << (rec.events_topic.empty() ? "no ~events in the bag: one from the first odom"
                                     : "from " + rec.events_topic)
        << "):\n";
    out << "  " << std::right << std::setw(3) << "#"
        << "  " << std::left << std::setw(34) << "reason" << std::right << std::setw(14)
        << "start s" << std::setw(10) << "length s" << std::setw(8) << "odom" << std::setw(11)
        << "|w| rad/s" << std::setw(11) << "orient rad" << std::setw(11) << "pos m" << std::setw(11)
        << "energy" << std::setw(11) << "momentum" << std::setw(11) << "||q|-1|" << std::setw(11)
        << "gap m" << std::setw(11) << "E rise" << std::setw(11) << "Jellett"
        << "\n";
    for (std::size_t k = 0; k < p.segments.size(); ++k) {
      const SegmentResult& s = p.segments[k];
      // "slide (contact, edge_contact)", "lift_off (separation)", "start".
      std::string reason = s.plan.reason;
      const bool detailed = !s.plan.detail.empty() && s.plan.detail != s.plan.reason;
      if (s.kind != SegmentKind::flight) {
        reason += " (" + segment_kind_name(s.kind) + (detailed ? ", " + s.plan.detail : "") + ")";
      } else if (detailed) {
        reason += " (" + s.plan.detail + ")";
      }
      out << "  " << std::right << std::setw(3) << k << "  " << std::left << std::setw(34) << reason
          << std::right << std::setw(14) << short_stamp_text(s.plan.start_ns) << std::setw(10)
          << fixed(s.duration_s, 3) << std::setw(8) << s.samples << std::setw(11)
          << fixed(s.max_angular_speed_radps, 3);
      if (s.samples == 0) {
        out << "  (no odom in this segment)\n";
        continue;
      }
      const bool flight = s.kind == SegmentKind::flight;
      const bool conserving = s.kind != SegmentKind::contact;
      out << std::setw(11) << (s.predicted ? sci(s.max_orientation_error) : "n/a") << std::setw(11)
          << (s.predicted ? sci(s.max_position_error) : "n/a") << std::setw(11)
          << (conserving ? sci(s.max_energy_drift) : "-") << std::setw(11)
          << (conserving ? sci(s.max_momentum_drift) : "-") << std::setw(11)
          << sci(s.max_quat_norm_error) << std::setw(11) << (s.board ? sci(s.min_gap_m) : "-")
          << std::setw(11) << (flight || conserving ? "-" : sci(s.max_energy_rise)) << std::setw(11)
          << (s.jellett_conserved ? sci(s.max_jellett_drift) : "-") << "\n";
      if (s.kind == SegmentKind::rest && s.rest_moved > 0) {
        out << "       rest: " << s.rest_moved << " samples moved (largest "
            << sci(s.rest_max_move_m) << " m)\n";
      }
      if (!s.note.empty()) out << "       note: " << s.note << "\n";
    }
    double m[5] = {0, 0, 0, 0, 0};
    double rise = 0.0, gap = INFINITY, jellett = 0.0;
    std::size_t moved = 0;
    bool board = false;
    for (const SegmentResult& s : p.segments) {
      m[0] = std::fmax(m[0], s.max_quat_norm_error);
      if (s.kind != SegmentKind::contact) m[1] = std::fmax(m[1], s.max_energy_drift);
      if (s.kind != SegmentKind::contact) m[2] = std::fmax(m[2], s.max_momentum_drift);
      if (s.predicted) m[3] = std::fmax(m[3], s.max_orientation_error);
      if (s.predicted) m[4] = std::fmax(m[4], s.max_position_error);
      if (s.kind == SegmentKind::contact) rise = std::fmax(rise, s.max_energy_rise);
      if (s.board && s.samples > 0) gap = std::fmin(gap, s.min_gap_m);
      if (s.jellett_conserved) jellett = std::fmax(jellett, s.max_jellett_drift);
      moved += s.rest_moved;
      board = board || s.board;
    }
    out << "\nphysics (" << rec.odom_topic << ", " << p.samples.size() << " samples, "
        << p.segments.size() << " segments), maxima over the run:\n"
        << "  max | |q| - 1 |        " << sci(m[0]) << "\n"
        << "  energy drift           " << sci(m[1]) << " (relative)\n"
        << "  momentum drift         " << sci(m[2]) << " (relative, world L)\n"
        << "  orientation error      " << sci(m[3]) << " rad (vs closed form)\n"
        << "  position error         " << sci(m[4]) << " m (vs closed form)\n"
        << "  energy rise            " << sci(rise) << " (relative, contact segments)\n"
        << "  smallest gap           " << (board ? sci(gap) : "n/a (no board in ~info)")
        << " m (above the board's top or the table)\n"
        << "  Jellett drift          " << sci(jellett) << " (relative, where conserved)\n"
        << "  rest samples moved     " << moved << "\n";
    auto print_non_finite = [&](const NonFiniteValues& v, const std::string& what) {
      if (v.count == 0) return;
      out << "  non-finite values      " << v.count << " " << what << " (first at "
          << short_stamp_text(v.first_stamp_ns) << " s, " << v.first_field
          << "), left out of the maxima above\n";
    };
    print_non_finite(p.non_finite_odom, "~odom samples");
    print_non_finite(p.non_finite_events, "~events messages");
  }

  if (!report.stones.empty()) print_stones(out, report);
  if (report.overlap) {
    const StoneOverlapResult& o = *report.overlap;
    out << "\nstone overlap (" << rec.stones_topic << ", " << o.snapshots
        << " messages with two stones or more, " << o.pairs_measured
        << " pair distances within reach): ";
    if (std::isfinite(o.min_gap_m)) {
      out << "smallest gap " << sci(o.min_gap_m) << " m, " << o.stone_a << " and " << o.stone_b
          << " at " << short_stamp_text(o.stamp_ns) << " s\n";
    } else {
      out << "no two stones within reach of each other\n";
    }
    constexpr std::size_t kShown = 10;
    for (std::size_t i = 0; i < o.overlaps.size() && i < kShown; ++i) {
      const PairOverlap& p = o.overlaps[i];
      out << "  overlap " << p.stone_a << " and " << p.stone_b << ": " << sci(p.depth_m)
          << " m deep at " << short_stamp_text(p.stamp_ns) << " s (" << p.stamps << " messages)\n";
    }
    if (o.overlaps.size() > kShown) {
      out << "  ... " << o.overlaps.size() - kShown << " more overlapping pairs\n";
    }
  }
  if (report.islands) {
    const StoneIslandResult& is = *report.islands;
    out << "\nstone islands (stones in contact with each other, from their events): "
        << is.islands.size();
    if (!is.islands.empty()) {
      const StoneIsland& w = is.islands[is.worst];
      out << "; worst total energy rise " << sci(w.max_energy_rise) << " (relative) at "
          << short_stamp_text(w.worst_stamp_ns) << " s, stones " << join(w.members, ", ") << " ("
          << w.snapshots << " messages)";
    }
    out << "\n";
  }

  out << "\nchecks:\n";
  std::size_t failed = 0;
  for (const Check& c : report.checks) {
    if (!c.pass) ++failed;
    out << "  " << (c.pass ? "ok  " : "FAIL") << "  " << std::left << std::setw(24) << c.figure
        << std::setw(28) << c.subject << std::right << " " << sci(c.value) << " <= " << sci(c.limit)
        << "  (" << c.basis << ")\n";
  }
  for (const std::string& problem : report.problems) out << "missing: " << problem << "\n";
  out << "\nresult: " << (failed == 0 ? "ok" : "FAIL") << ", " << report.checks.size() - failed
      << " of " << report.checks.size() << " checks within limits"
      << (report.partial() ? ", partial report (see 'missing')" : "") << "\n";
}

void write_csv(const std::string& path, const Report& report) {
  std::ofstream out(path);
  if (!out) throw OutputError("cannot write CSV " + path);
  out << "segment,stamp_s,time_s,t_segment_s,quat_norm_error,energy_drift,momentum_drift,"
         "orientation_error_rad,position_error_m,angular_speed_radps,gap_m,energy_rise,"
         "jellett_drift\n";
  if (report.physics) {
    const auto& samples = report.physics->samples;
    const std::int64_t t0 = samples.empty() ? 0 : samples.front().stamp_ns;
    out << std::setprecision(12);
    for (const PhysicsSample& s : samples) {
      out << s.segment << "," << short_stamp_text(s.stamp_ns).substr(0) << ","
          << fixed(seconds_between(t0, s.stamp_ns), 9) << "," << fixed(s.t_s, 9) << ","
          << s.quat_norm_error << "," << s.energy_drift << "," << s.momentum_drift << ","
          << s.orientation_error << "," << s.position_error << "," << s.angular_speed_radps << ","
          << s.gap_m << "," << s.energy_rise << "," << s.jellett_drift << "\n";
    }
  }
  out.flush();
  if (!out) throw OutputError("error while writing CSV " + path);
}

void write_plot(const std::string& png_path, const Report& report, const std::string& csv_path) {
  if (!report.physics || report.physics->samples.empty()) {
    throw OutputError("no physics time series to plot (needs ~info and ~odom)");
  }
  std::string data = csv_path;
  std::string temporary;
  if (data.empty()) {
    char name[] = "/tmp/bag_report_XXXXXX";
    const int fd = ::mkstemp(name);
    if (fd < 0) throw OutputError("cannot create a temporary file for the plot data");
    ::close(fd);
    temporary = data = name;
    write_csv(data, report);
  }
  // Quote for gnuplot's single-quoted strings (no escapes inside them except '').
  auto quote = [](const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("''") : std::string(1, c);
    return q + "'";
  };
  // Zeros cannot be shown on a log axis: floor them at 1e-18 so the line stays visible.
  std::ostringstream script;
  script << "set terminal png size 1200,900 noenhanced\n"
         << "set output " << quote(png_path) << "\n"
         << "set datafile separator ','\n"
         << "set key outside right\n"
         << "set logscale y\nset format y '%.0e'\nset grid\n"
         << "f(x) = (x > 1e-18) ? x : 1e-18\n"
         << "set multiplot layout 2,1 title " << quote("bag_report " + report.recording.path)
         << "\n";
  // Mark the segment starts: the prediction restarts there.
  const auto& samples = report.physics->samples;
  const std::int64_t t0 = samples.front().stamp_ns;
  int arrow = 1;
  for (const SegmentResult& s : report.physics->segments) {
    if (arrow > 200) break;
    script << "set arrow " << arrow++ << " from " << seconds_between(t0, s.plan.start_ns)
           << ", graph 0 to " << seconds_between(t0, s.plan.start_ns)
           << ", graph 1 nohead dashtype 2 linecolor rgb 'gray'\n";
  }
  script << "set title 'error against the exact closed form'\nset xlabel 'time (s)'\n"
         << "plot " << quote(data) << " using 3:(f($8)) with lines title 'orientation (rad)', "
         << "'' using 3:(f($9)) with lines title 'position (m)'\n"
         << "set title 'invariants (relative drift)'\n"
         << "plot " << quote(data) << " using 3:(f($5)) with lines title '| |q| - 1 |', "
         << "'' using 3:(f($6)) with lines title 'energy', "
         << "'' using 3:(f($7)) with lines title 'angular momentum'\n"
         << "unset multiplot\n";

  FILE* pipe = ::popen("gnuplot 1>&2", "w");
  if (pipe == nullptr) throw OutputError("cannot run gnuplot (install gnuplot-nox)");
  std::fputs(script.str().c_str(), pipe);
  const int status = ::pclose(pipe);
  if (!temporary.empty()) std::remove(temporary.c_str());
  if (status != 0) {
    throw OutputError("gnuplot failed (exit status " + std::to_string(status) + ") writing " +
                      png_path + "; is gnuplot installed?");
  }
  std::ifstream check(png_path, std::ios::binary);
  if (!check) throw OutputError("gnuplot did not write " + png_path);
}

}  // namespace bag
}  // namespace virtual_go
