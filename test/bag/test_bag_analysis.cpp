// bag_report's analysis units on plain data: no bag, no master.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "support/test_bags.h"
#include "virtual_go/bag/options.h"
#include "virtual_go/bag/physics_check.h"
#include "virtual_go/bag/report.h"
#include "virtual_go/bag/stamp_statistics.h"
#include "virtual_go/bag/thresholds.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/flight/integrator_registry.h"

namespace vb = virtual_go::bag;

namespace {

constexpr std::int64_t kMs = 1000000;

vb::RecordingInfo info(const std::string& integrator = "exact") {
  vb::RecordingInfo i;
  i.topic = "/stone/info";
  i.mass = virtual_go_test::kMass;
  i.principal_moments_body = {virtual_go_test::kI1, virtual_go_test::kI1, virtual_go_test::kI3};
  i.model = "rigid_body";
  i.integrator = integrator;
  i.dt_s = 1e-3;
  i.dt_ns = kMs;
  i.rate_hz = 50.0;
  i.gravity_world = {0.0, 0.0, -9.80665};
  return i;
}

vb::OdomSample odom_at(std::int64_t stamp_ns, double t) {
  const virtual_go_test::TrueState s = virtual_go_test::true_state(t);
  vb::OdomSample o;
  o.stamp_ns = stamp_ns;
  o.position_world = s.position;
  o.orientation_raw = s.orientation;
  o.velocity_body = s.orientation.conjugate() * s.velocity_world;
  o.angular_velocity_body = s.angular_velocity_body;
  return o;
}

virtual_go::SegmentEvent event_at(std::int64_t stamp_ns, const std::string& reason) {
  virtual_go::SegmentEvent e;
  e.stamp_ns = stamp_ns;
  e.reason = virtual_go::parse_event_reason(reason);
  return e;
}

TEST(StampStatistics, RegularStamps) {
  std::vector<std::int64_t> stamps;
  for (int i = 0; i < 101; ++i) stamps.push_back(5000 * kMs + i * 20 * kMs);
  const vb::StampStatistics s = vb::compute_stamp_statistics(stamps);
  EXPECT_EQ(s.count, 101u);
  EXPECT_NEAR(s.mean_rate_hz, 50.0, 1e-9);
  EXPECT_NEAR(s.period_p50_s, 0.02, 1e-12);
  EXPECT_NEAR(s.period_p99_s, 0.02, 1e-12);
  EXPECT_NEAR(s.period_max_s, 0.02, 1e-12);
  EXPECT_TRUE(s.gaps.empty());
  EXPECT_TRUE(s.repeated.empty());
  EXPECT_TRUE(s.non_increasing.empty());
}

TEST(StampStatistics, GapRepeatAndBackwards) {
  const std::vector<std::int64_t> stamps = {0,        10 * kMs, 20 * kMs, 20 * kMs, 30 * kMs,
                                            70 * kMs, 80 * kMs, 75 * kMs, 90 * kMs};
  const vb::StampStatistics s = vb::compute_stamp_statistics(stamps);
  ASSERT_EQ(s.repeated.size(), 1u);
  EXPECT_EQ(s.repeated[0].index, 3u);
  ASSERT_EQ(s.non_increasing.size(), 1u);
  EXPECT_EQ(s.non_increasing[0].stamp_ns, 75 * kMs);
  ASSERT_EQ(s.gaps.size(), 1u);  // 30 -> 70 ms is 4x the 10 ms median
  EXPECT_EQ(s.gaps[0].step_ns, 40 * kMs);
  EXPECT_NEAR(s.period_max_s, 0.04, 1e-12);
  EXPECT_NEAR(s.period_p50_s, 0.01, 1e-12);
}

TEST(StampStatistics, DegenerateInputs) {
  EXPECT_EQ(vb::compute_stamp_statistics({}).count, 0u);
  const vb::StampStatistics one = vb::compute_stamp_statistics({42});
  EXPECT_EQ(one.count, 1u);
  EXPECT_EQ(one.mean_rate_hz, 0.0);
  EXPECT_EQ(vb::percentile({}, 50.0), 0.0);
  EXPECT_EQ(vb::percentile({3.0, 1.0, 2.0, 4.0}, 50.0), 2.0);
  EXPECT_EQ(vb::percentile({3.0, 1.0, 2.0, 4.0}, 99.0), 4.0);
}

TEST(PlanSegments, NoEventsIsOneSegmentFromTheFirstOdom) {
  std::vector<vb::OdomSample> odom = {odom_at(10, 0), odom_at(20, 0), odom_at(30, 0)};
  const auto plans = vb::plan_segments(odom, {});
  ASSERT_EQ(plans.size(), 1u);
  EXPECT_FALSE(plans[0].from_event);
  EXPECT_EQ(plans[0].start_ns, 10);
  EXPECT_EQ(plans[0].end, 3u);
}

TEST(PlanSegments, EventsSplitByStamp) {
  std::vector<vb::OdomSample> odom;
  for (int i = 0; i < 10; ++i) odom.push_back(odom_at(100 + 10 * i, 0));
  // The start event, a reset between samples 4 and 5, an event after the last sample.
  const auto plans = vb::plan_segments(
      odom, {event_at(100, "start"), event_at(145, "reset"), event_at(500, "set_state")});
  ASSERT_EQ(plans.size(), 3u);
  EXPECT_EQ(plans[0].first, 0u);
  EXPECT_EQ(plans[0].end, 5u);
  EXPECT_EQ(plans[1].reason, "reset");
  EXPECT_EQ(plans[1].start_ns, 145);
  EXPECT_EQ(plans[1].first, 5u);
  EXPECT_EQ(plans[1].end, 10u);
  EXPECT_EQ(plans[2].first, plans[2].end);  // listed, but empty
}

TEST(PlanSegments, TimeJumpBackwards) {
  // A looping bag: stamps 100..140, then 50..70 with a time_jump event at 50.
  std::vector<vb::OdomSample> odom;
  for (std::int64_t s : {100, 110, 120, 130, 140, 50, 60, 70}) odom.push_back(odom_at(s, 0));
  const auto plans = vb::plan_segments(odom, {event_at(100, "start"), event_at(50, "time_jump")});
  ASSERT_EQ(plans.size(), 2u);
  EXPECT_EQ(plans[0].end, 5u);
  EXPECT_EQ(plans[1].reason, "time_jump");
  EXPECT_EQ(plans[1].first, 5u);
  EXPECT_EQ(plans[1].end, 8u);
  // Without the event the jump still starts a new segment (and says so).
  const auto unexplained = vb::plan_segments(odom, {event_at(100, "start")});
  ASSERT_EQ(unexplained.size(), 2u);
  EXPECT_EQ(unexplained[1].reason, "stamps went backwards (no event)");
}

TEST(CheckPhysics, ExactRecordingHasNoError) {
  std::vector<vb::OdomSample> odom;
  for (int i = 0; i <= 100; ++i) odom.push_back(odom_at(i * 20 * kMs, i * 0.02));
  const vb::PhysicsResult r = vb::check_physics(info(), odom, {});
  ASSERT_EQ(r.segments.size(), 1u);
  const vb::SegmentResult& s = r.segments[0];
  EXPECT_TRUE(s.predicted);
  EXPECT_LT(s.max_orientation_error, 1e-12);
  EXPECT_LT(s.max_position_error, 1e-12);
  EXPECT_LT(s.max_energy_drift, 1e-12);
  EXPECT_LT(s.max_momentum_drift, 1e-12);
  EXPECT_LT(s.max_quat_norm_error, 1e-12);
  EXPECT_NEAR(s.duration_s, 2.0, 1e-12);
  EXPECT_GT(s.max_angular_speed_radps, 25.0);
  EXPECT_EQ(r.samples.size(), 101u);
}

TEST(CheckPhysics, DetectsOrientationAndPositionErrors) {
  std::vector<vb::OdomSample> odom;
  for (int i = 0; i <= 10; ++i) odom.push_back(odom_at(i * 20 * kMs, i * 0.02));
  odom[5].orientation_raw = Eigen::Quaterniond(Eigen::AngleAxisd(1e-6, Eigen::Vector3d::UnitZ())) *
                            odom[5].orientation_raw;
  odom[7].position_world.x() += 1e-6;
  odom[8].orientation_raw.coeffs() *= 1.001;  // not unit
  const vb::PhysicsResult r = vb::check_physics(info(), odom, {});
  EXPECT_NEAR(r.samples[5].orientation_error, 1e-6, 1e-9);
  EXPECT_NEAR(r.samples[7].position_error, 1e-6, 1e-12);
  EXPECT_NEAR(r.samples[8].quat_norm_error, 1e-3, 1e-9);
  EXPECT_LT(r.samples[8].orientation_error, 1e-12) << "normalised before comparing";
}

TEST(CheckPhysics, MomentumDriftIsRelativeToTheFirstL) {
  std::vector<vb::OdomSample> odom{odom_at(0, 0.0), odom_at(20 * kMs, 0.02)};
  odom[1].angular_velocity_body *= 3.0;  // |L| = 3 |L0|: drift 2 against |L0| (not 2/3)
  const vb::PhysicsResult r = vb::check_physics(info(), odom, {});
  EXPECT_NEAR(r.samples[1].momentum_drift, 2.0, 1e-9);

  // Starting at rest there is no |L0|: the segment's largest |L| is the scale instead.
  odom[0].angular_velocity_body.setZero();
  odom[1].angular_velocity_body.setZero();
  EXPECT_EQ(vb::check_physics(info(), odom, {}).segments[0].max_momentum_drift, 0.0);
  odom[1].angular_velocity_body = {0.0, 0.0, 5.0};
  EXPECT_NEAR(vb::check_physics(info(), odom, {}).samples[1].momentum_drift, 1.0, 1e-12);
}

TEST(CheckPhysics, NonFiniteValuesAreCountedNotFatal) {
  std::vector<vb::OdomSample> odom;
  for (int i = 0; i <= 10; ++i) odom.push_back(odom_at(i * 20 * kMs, i * 0.02));
  odom[3].velocity_body.y() = NAN;
  odom[5].position_world.x() = INFINITY;
  const vb::PhysicsResult r = vb::check_physics(info(), odom, {});
  EXPECT_EQ(r.non_finite_odom.count, 2u);
  EXPECT_EQ(r.non_finite_odom.first_stamp_ns, 60 * kMs);
  EXPECT_EQ(r.non_finite_odom.first_field, "linear velocity");
  EXPECT_TRUE(std::isnan(r.samples[3].energy_drift));
  EXPECT_TRUE(std::isnan(r.samples[5].orientation_error));
  ASSERT_EQ(r.segments.size(), 1u);
  EXPECT_TRUE(r.segments[0].predicted);
  EXPECT_LT(r.segments[0].max_orientation_error, 1e-12) << "the other samples keep their figures";

  vb::Recording rec;
  rec.info = info();
  rec.odom_topic = "/stone/odom";
  const auto checks = vb::run_checks(rec, {}, &r, vb::LimitOverrides{});
  bool counted = false;
  for (const vb::Check& c : checks) {
    if (c.figure == "non-finite values") counted = !c.pass && c.value == 2.0;
  }
  EXPECT_TRUE(counted) << "a NaN sample must fail --strict";

  // A non-finite event cannot start a prediction; it is counted too.
  virtual_go::SegmentEvent bad = event_at(0, "start");
  bad.state.angular_momentum_world.z() = NAN;
  const vb::PhysicsResult e = vb::check_physics(info(), {odom_at(0, 0.0)}, {bad});
  EXPECT_EQ(e.non_finite_events.count, 1u);
  ASSERT_EQ(e.segments.size(), 1u);
  EXPECT_FALSE(e.segments[0].predicted);
  EXPECT_NE(e.segments[0].note.find("angular momentum"), std::string::npos) << e.segments[0].note;
}

TEST(CheckPhysics, BadInfoIsRejected) {
  vb::RecordingInfo bad = info();
  bad.model = "quantum";
  EXPECT_THROW(vb::check_physics(bad, {odom_at(0, 0)}, {}), virtual_go::InvalidArgument);
  bad = info();
  bad.mass = 0.0;
  EXPECT_THROW(vb::check_physics(bad, {odom_at(0, 0)}, {}), virtual_go::InvalidArgument);
}

TEST(CheckPhysics, NonAxisymmetricInertiaHasNoPrediction) {
  vb::RecordingInfo i = info();
  i.principal_moments_body.y() *= 1.5;
  const vb::PhysicsResult r = vb::check_physics(i, {odom_at(0, 0), odom_at(kMs, 0.001)}, {});
  ASSERT_EQ(r.segments.size(), 1u);
  EXPECT_FALSE(r.segments[0].predicted);
  EXPECT_NE(r.segments[0].note.find("axisymmetric"), std::string::npos);
}

TEST(Thresholds, BoundsFollowTheIntegrator) {
  vb::SegmentResult seg;
  seg.max_angular_speed_radps = 20.0;
  seg.duration_s = 5.0;
  const vb::LimitOverrides none;
  const double g = 9.80665;
  EXPECT_DOUBLE_EQ(vb::physics_bounds("exact", 1e-3, seg, g, none).orientation_error, 1e-9);
  const double split = vb::physics_bounds("splitting", 1e-3, seg, g, none).orientation_error;
  EXPECT_NEAR(split, 1e-9 + 2.0 * 0.02 * 0.02 * 20.0 * 5.0, 1e-12);
  EXPECT_GT(vb::physics_bounds("euler", 1e-3, seg, g, none).position_error, 0.5 * g * 1e-3 * 5.0);
  EXPECT_THROW(vb::physics_bounds("leapfrog", 1e-3, seg, g, none), virtual_go::InvalidArgument);
  vb::LimitOverrides given;
  given.orientation_error = 0.5;
  EXPECT_EQ(vb::physics_bounds("exact", 1e-3, seg, g, given).orientation_error, 0.5);
}

TEST(Thresholds, EveryIntegratorHasABound) {
  for (const std::string& name : virtual_go::integrator_names()) {
    EXPECT_NE(vb::default_limits_text().find("  " + name + " "), std::string::npos) << name;
  }
  try {
    vb::physics_bounds("leapfrog", 1e-3, vb::SegmentResult{}, 9.8, vb::LimitOverrides{});
    ADD_FAILURE() << "no throw";
  } catch (const virtual_go::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("known: euler rk4 splitting exact"), std::string::npos)
        << e.what();
  }
}

// README.md restates the constants for readers; this keeps it honest.
TEST(Thresholds, ReadmeTableMatchesTheCode) {
  std::ifstream readme(VG_README);
  ASSERT_TRUE(readme) << VG_README;
  std::map<std::string, std::vector<double>> rows;
  std::string line;
  while (std::getline(readme, line)) {
    if (line.rfind("| ", 0) != 0) continue;
    std::vector<std::string> cells;
    std::stringstream in(line.substr(1));
    std::string cell;
    while (std::getline(in, cell, '|')) cells.push_back(cell);
    if (cells.size() != 5) continue;
    const std::string name = cells[0].substr(1, cells[0].size() - 2);
    if (virtual_go::find_integrator(name) == nullptr) continue;
    for (std::size_t i = 1; i < cells.size(); ++i) {
      rows[name].push_back(std::strtod(cells[i].c_str(), nullptr));  // "0 (so ...)" reads 0
    }
  }
  for (const virtual_go::IntegratorInfo& b : virtual_go::integrators().entries()) {
    ASSERT_EQ(rows[b.name].size(), 4u) << "no README row for " << b.name;
    const std::vector<double>& r = rows[b.name];
    EXPECT_EQ(r[0], b.order) << b.name;
    EXPECT_EQ(r[1], b.error_bound.k_orientation) << b.name;
    EXPECT_EQ(r[2], b.error_bound.k_energy) << b.name;
    EXPECT_EQ(r[3], b.error_bound.k_gravity) << b.name;
  }
}

TEST(Thresholds, NanFigureFails) {
  vb::Recording rec;
  rec.info = info();
  vb::PhysicsResult physics;
  vb::SegmentResult seg;
  seg.samples = 3;
  seg.predicted = false;
  seg.note = "no closed form";
  physics.segments.push_back(seg);
  const auto checks = vb::run_checks(rec, {}, &physics, vb::LimitOverrides{});
  bool orientation_failed = false;
  for (const vb::Check& c : checks) {
    if (c.figure.rfind("orientation", 0) == 0) orientation_failed = !c.pass;
  }
  EXPECT_TRUE(orientation_failed) << "a figure that cannot be computed must not pass --strict";
}

// An event after its rounded-down stamp (sub-ns offset) lies after a sample at that stamp; one
// with offset 0 at the same stamp takes it, as before.
TEST(PlanSegments, SubNanosecondOffsetKeepsASampleAtTheStampBeforeTheEvent) {
  std::vector<vb::OdomSample> odom;
  for (int i = 0; i < 4; ++i) odom.push_back(odom_at(1000 * kMs + i * 20 * kMs, i * 0.02));
  std::vector<virtual_go::SegmentEvent> events = {event_at(1000 * kMs, "start"),
                                                  event_at(1020 * kMs, "impact")};
  events[1].time_offset_s = 0.4e-9;
  const std::vector<vb::SegmentPlan> plans = vb::plan_segments(odom, events);
  ASSERT_EQ(plans.size(), 2u);
  EXPECT_EQ(plans[0].end, 2u);  // the sample at 1020 ms precedes the impact at 1020 ms + 0.4 ns
  EXPECT_EQ(plans[1].first, 2u);
  EXPECT_EQ(plans[1].start_offset_s, 0.4e-9);
  events[1].time_offset_s = 0.0;
  EXPECT_EQ(vb::plan_segments(odom, events)[1].first, 1u);
}

TEST(SegmentKind, ByReasonAndAnImpactFollowedAtTheSameInstant) {
  std::vector<virtual_go::SegmentEvent> events = {
      event_at(1, "start"), event_at(2, "impact"), event_at(3, "impact"),
      event_at(3, "slide"), event_at(4, "roll"),   event_at(5, "rim"),
      event_at(6, "rest"),  event_at(7, "wake"),   event_at(8, "impact")};
  events[3].time_offset_s = 0.0;
  const vb::SegmentKind expected[] = {
      vb::SegmentKind::flight,  vb::SegmentKind::flight,  vb::SegmentKind::contact,
      vb::SegmentKind::contact, vb::SegmentKind::contact, vb::SegmentKind::contact,
      vb::SegmentKind::rest,    vb::SegmentKind::flight,  vb::SegmentKind::flight};
  for (std::size_t i = 0; i < events.size(); ++i) {
    EXPECT_EQ(vb::segment_kind(events, i), expected[i])
        << i << " " << virtual_go::event_reason_name(events[i].reason);
  }
  // The same stamp but another offset is another instant: that impact flies.
  events[3].time_offset_s = 0.5e-9;
  EXPECT_EQ(vb::segment_kind(events, 2), vb::SegmentKind::flight);
}

// README.md's limits table restates the contact limits; --help lists them and their options.
TEST(Thresholds, ContactLimitsInReadmeAndHelp) {
  std::ifstream readme(VG_README);
  ASSERT_TRUE(readme) << VG_README;
  std::map<std::string, std::string> rows;
  std::string line;
  while (std::getline(readme, line)) {
    if (line.rfind("| ", 0) != 0) continue;
    const std::size_t bar = line.find(" | ", 2);
    if (bar == std::string::npos) continue;
    rows[line.substr(2, bar - 2)] = line.substr(bar + 3);
  }
  for (int c = 0; c < vb::kContactLimitCount; ++c) {
    const vb::ContactLimit& limit = vb::contact_limit(c);
    ASSERT_EQ(rows.count(limit.figure), 1u) << "no README row for " << limit.figure;
    const std::string& cell = rows[limit.figure];
    EXPECT_EQ(std::strtod(cell.c_str(), nullptr), limit.default_limit) << cell;
    EXPECT_NE(cell.find(std::string("`") + limit.option + "`"), std::string::npos) << cell;
    EXPECT_NE(vb::usage_text().find(limit.option), std::string::npos) << limit.option;
    EXPECT_NE(vb::usage_text().find(limit.meaning), std::string::npos) << limit.option;
    // The option sets the limit.
    const vb::Options o = vb::parse_options({"a.bag", limit.option, "0.5"});
    ASSERT_TRUE(o.limits.contact[c].has_value());
    EXPECT_EQ(*o.limits.contact[c], 0.5);
  }
}

TEST(Options, Parse) {
  const vb::Options o = vb::parse_options(
      {"run.bag", "--csv", "a.csv", "--strict", "--max-gaps", "3", "--node-namespace", "/s"});
  EXPECT_EQ(o.bag_path, "run.bag");
  EXPECT_EQ(o.csv_path, "a.csv");
  EXPECT_TRUE(o.strict);
  EXPECT_EQ(o.limits.max_gaps, 3u);
  EXPECT_EQ(o.node_namespace, "/s");
  EXPECT_TRUE(vb::parse_options({"--help"}).help);
  EXPECT_THROW(vb::parse_options({}), vb::UsageError);
  EXPECT_THROW(vb::parse_options({"a.bag", "b.bag"}), vb::UsageError);
  EXPECT_THROW(vb::parse_options({"a.bag", "--csv"}), vb::UsageError);
  EXPECT_THROW(vb::parse_options({"a.bag", "--max-energy-drift", "-1"}), vb::UsageError);
  EXPECT_THROW(vb::parse_options({"a.bag", "--max-energy-drift", "nan"}), vb::UsageError);
}

}  // namespace

namespace {

// A placed stone of the default set's black size (22.2 mm wide, size 33: 9.2 mm).
vb::StoneTrack track(const std::string& name, double width_m = 0.0222, double height_m = 0.0092) {
  vb::StoneTrack t;
  t.name = name;
  t.color = "black";
  t.width_m = width_m;
  t.height_m = height_m;
  t.mass_kg = 5e-3;
  return t;
}

// Two flat stones (axis up) at their centres, one ~stones message.
vb::StonesSnapshot flat_pair(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  vb::StonesSnapshot s;
  s.stamp_ns = 7 * kMs;
  s.track = {0, 1};
  s.position_world = {a, b};
  s.orientation_raw = {Eigen::Quaterniond::Identity(), Eigen::Quaterniond::Identity()};
  return s;
}

}  // namespace

// Two flat lenses one above the other: the caps' tops on the common axis are the closest points,
// gap = dz - c_A - c_B, and overlapping the shortest way apart is straight up (depth
// c_A + c_B - dz). Side by side with the centres farther apart than a_A + a_B (rim to rim: gap
// d - a_A - a_B > 0) they are not measured.
TEST(StoneOverlap, FlatStonesAgainstTheirClosedForms) {
  const std::vector<vb::StoneTrack> tracks = {track("black_1"), track("white_1", 0.0219, 0.009)};
  const double a_sum = 0.0222 / 2 + 0.0219 / 2, c_sum = 0.0092 / 2 + 0.009 / 2;

  const vb::StoneOverlapResult apart =
      vb::check_stone_overlaps(tracks, {flat_pair({0.1, 0.2, 0.0}, {0.1, 0.2, c_sum + 3e-4})});
  EXPECT_EQ(apart.pairs_measured, 1u);
  EXPECT_NEAR(apart.min_gap_m, 3e-4, 1e-15);
  EXPECT_TRUE(apart.overlaps.empty());

  const vb::StoneOverlapResult stacked =
      vb::check_stone_overlaps(tracks, {flat_pair({0.0, 0.0, 0.0}, {0.0, 0.0, c_sum - 2e-4})});
  EXPECT_NEAR(stacked.min_gap_m, -2e-4, 1e-12);
  ASSERT_EQ(stacked.overlaps.size(), 1u);
  EXPECT_EQ(stacked.overlaps[0].stone_a, "black_1");
  EXPECT_EQ(stacked.overlaps[0].stone_b, "white_1");
  EXPECT_NEAR(stacked.overlaps[0].depth_m, 2e-4, 1e-12);
  EXPECT_EQ(stacked.overlaps[0].stamp_ns, 7 * kMs);

  const vb::StoneOverlapResult far =
      vb::check_stone_overlaps(tracks, {flat_pair({0.0, 0.0, 0.0}, {a_sum + 1e-6, 0.0, 0.0})});
  EXPECT_EQ(far.snapshots, 1u);
  EXPECT_EQ(far.pairs_measured, 0u);
  EXPECT_TRUE(std::isinf(far.min_gap_m));

  // Over --max-overlap, the check names the pair.
  vb::Recording rec;
  const auto checks = vb::run_checks(rec, {}, nullptr, vb::LimitOverrides{}, {}, &stacked);
  ASSERT_EQ(checks.size(), 1u);
  EXPECT_FALSE(checks[0].pass);
  EXPECT_EQ(checks[0].subject, "stones black_1, white_1");
  EXPECT_NEAR(checks[0].value, 2e-4, 1e-12);
}

// Several stones: each placed stone is held to its own events and samples, and a check names
// its stone. black_1 is dropped without spin (its flight against the parabola written here),
// black_2 is set down at rest and one of its samples is moved by 1 um; the events of both do
// not split the initial stone's segments.
TEST(ManyStones, EachStoneOnItsOwnEventsAndAMovedRestingStoneIsNamed) {
  const Eigen::Vector3d g(0.0, 0.0, -9.80665);
  const Eigen::Vector3d x0(0.05, -0.02, 0.03), v0(0.1, 0.0, 0.2);
  vb::Recording rec;
  rec.info = info();
  rec.odom_topic = "/stone/odom";
  rec.stones_topic = "/stone/stones";
  rec.events_topic = "/stone/events";
  for (int i = 0; i <= 10; ++i) rec.odom.push_back(odom_at(i * 20 * kMs, i * 0.02));
  virtual_go::SegmentEvent start = event_at(0, "start");
  const virtual_go_test::TrueState s0 = virtual_go_test::true_state(0.0);
  start.state.position_world = s0.position;
  start.state.orientation = s0.orientation;
  start.state.velocity_world = s0.velocity_world;
  start.state.angular_momentum_world = s0.angular_momentum_world;
  start.stone = "stone";
  rec.events.push_back(start);

  vb::StoneTrack dropped = track("black_1");
  virtual_go::SegmentEvent place = event_at(40 * kMs, "place");
  place.stone = "black_1";
  place.state.position_world = x0;
  place.state.velocity_world = v0;
  rec.events.push_back(place);
  for (int i = 2; i <= 10; ++i) {
    const double t = (i - 2) * 0.02;
    vb::OdomSample o;
    o.stamp_ns = i * 20 * kMs;
    o.position_world = x0 + v0 * t + 0.5 * g * t * t;
    o.velocity_body = v0 + g * t;
    o.has_twist = i % 2 == 0;  // the odd ones are /tf poses
    dropped.samples.push_back(o);
  }
  vb::StoneTrack resting = track("black_2");
  for (const char* reason : {"place", "rest"}) {
    virtual_go::SegmentEvent e = event_at(60 * kMs, reason);
    e.stone = "black_2";
    e.state.position_world = {0.0, 0.022, 0.0046};
    rec.events.push_back(e);
  }
  for (int i = 3; i <= 10; ++i) {
    vb::OdomSample o;
    o.stamp_ns = i * 20 * kMs;
    o.position_world = {0.0, 0.022, 0.0046};
    resting.samples.push_back(o);
  }
  resting.samples[5].position_world.x() += 1e-6;
  rec.stone_tracks = {dropped, resting};

  const vb::Report report = vb::analyse(rec, vb::LimitOverrides{});
  ASSERT_TRUE(report.physics.has_value());
  EXPECT_EQ(report.physics->segments.size(), 1u) << "other stones' events split stone's";
  ASSERT_EQ(report.stones.size(), 2u);
  ASSERT_TRUE(report.stones[0].physics.has_value());
  const vb::PhysicsResult& b1 = *report.stones[0].physics;
  ASSERT_EQ(b1.segments.size(), 1u);
  EXPECT_TRUE(b1.segments[0].predicted);
  EXPECT_EQ(b1.segments[0].samples, 9u);
  EXPECT_LT(b1.segments[0].max_position_error, 1e-15);
  EXPECT_LT(b1.segments[0].max_energy_drift, 1e-14);
  ASSERT_TRUE(report.stones[1].physics.has_value());
  const vb::PhysicsResult& b2 = *report.stones[1].physics;
  ASSERT_EQ(b2.segments.size(), 2u);
  EXPECT_EQ(b2.segments[1].kind, vb::SegmentKind::rest);
  EXPECT_EQ(b2.segments[1].rest_moved, 1u);
  EXPECT_NEAR(b2.segments[1].rest_max_move_m, 1e-6, 1e-15);

  std::vector<std::string> failed;
  for (const vb::Check& c : report.checks) {
    if (!c.pass) failed.push_back(c.figure + ": " + c.subject);
  }
  ASSERT_EQ(failed.size(), 1u) << ::testing::PrintToString(failed);
  EXPECT_EQ(failed[0], "rest motion: stone black_2 segment 1 (rest, rest)");
  std::ostringstream printed;
  vb::print_report(printed, report);
  EXPECT_NE(printed.str().find("black_2"), std::string::npos) << printed.str();
}

namespace {

// Two stones of equal mass in one contact from t = 0 (each one's slide event naming the other),
// flat at z = 0 (no potential energy) and 0.05 m apart: black_1 starts at 0.2 m/s along x and
// hands its speed over to white_1, v_black = 0.2 cos(theta), v_white = 0.2 sin(theta) at
// theta = 0, 0.4, 0.8, 1.2 (t = 0, 20, 40, 60 ms), so the sum of 1/2 m v^2 stays 1/2 m 0.04 while
// white_1's own energy rises from zero. white_gain scales white_1's last speed.
vb::Recording momentum_exchange(double white_gain) {
  vb::Recording rec;
  rec.info = info();
  rec.stones_topic = "/stone/stones";
  rec.events_topic = "/stone/events";
  const std::string names[2] = {"black_1", "white_1"};
  const Eigen::Vector3d x0[2] = {{0.0, 0.0, 0.0}, {0.05, 0.0, 0.0}};
  for (int s = 0; s < 2; ++s) {
    virtual_go::SegmentEvent e = event_at(0, "slide");
    e.stone = names[s];
    e.other_stone = names[1 - s];
    e.state.position_world = x0[s];
    e.state.velocity_world = {s == 0 ? 0.2 : 0.0, 0.0, 0.0};
    rec.events.push_back(e);
    rec.stone_tracks.push_back(track(names[s]));
  }
  for (int i = 0; i <= 3; ++i) {
    const double theta = 0.4 * i;
    const double speed[2] = {0.2 * std::cos(theta),
                             0.2 * std::sin(theta) * (i == 3 ? white_gain : 1.0)};
    vb::StonesSnapshot snap = flat_pair(x0[0], x0[1]);
    snap.stamp_ns = i * 20 * kMs;
    rec.snapshots.push_back(snap);
    for (int s = 0; s < 2; ++s) {
      vb::OdomSample o;
      o.stamp_ns = snap.stamp_ns;
      o.position_world = x0[s];
      o.velocity_body = {speed[s], 0.0, 0.0};
      rec.stone_tracks[s].samples.push_back(o);
    }
  }
  return rec;
}

std::vector<std::string> failed_checks(const vb::Report& report) {
  std::vector<std::string> failed;
  for (const vb::Check& c : report.checks) {
    if (!c.pass) failed.push_back(c.figure + ": " + c.subject);
  }
  return failed;
}

}  // namespace

// One stone slows, the other speeds up by as much energy: white_1's own energy rises (from 0 to
// 93 % of the total) yet the island's total does not, so nothing fails; with white_1's last speed
// raised so that the total gains 2e-9 of itself the island fails, naming both stones, and no
// per-stone energy rise does.
TEST(StoneIslands, TotalEnergyOfStonesInContactNeverRises) {
  const vb::Report kept = vb::analyse(momentum_exchange(1.0), vb::LimitOverrides{});
  ASSERT_TRUE(kept.islands.has_value());
  ASSERT_EQ(kept.islands->islands.size(), 1u);
  const vb::StoneIsland& island = kept.islands->islands[0];
  EXPECT_EQ(island.members, (std::vector<std::string>{"black_1", "white_1"}));
  EXPECT_EQ(island.start_ns, 0);
  EXPECT_EQ(island.snapshots, 4u);
  EXPECT_LT(island.max_energy_rise, 1e-15);
  ASSERT_EQ(kept.stones.size(), 2u);
  ASSERT_TRUE(kept.stones[1].physics.has_value());
  const vb::PhysicsResult& white = *kept.stones[1].physics;
  // white_1's rise on its own: all of its energy above the event's zero, relative to its own
  // scale (its largest energy so far), so 1; exempt within the island.
  double own_rise = 0.0;
  for (const vb::PhysicsSample& p : white.samples) own_rise = std::fmax(own_rise, p.energy_rise);
  EXPECT_NEAR(own_rise, 1.0, 1e-12);
  EXPECT_EQ(white.segments[0].max_energy_rise, 0.0);
  EXPECT_TRUE(failed_checks(kept).empty()) << ::testing::PrintToString(failed_checks(kept));
  std::ostringstream printed;
  vb::print_report(printed, kept);
  EXPECT_NE(printed.str().find("stone islands (stones in contact with each other, from their "
                               "events): 1; worst total energy rise"),
            std::string::npos)
      << printed.str();

  // Total at 60 ms: 0.04 (cos^2 + (g sin)^2), relative to the scale 0.04 (1/2 m cancels).
  const double gain = std::sqrt(1.0 + 2e-9 / std::pow(std::sin(1.2), 2));
  const vb::Report raised = vb::analyse(momentum_exchange(gain), vb::LimitOverrides{});
  ASSERT_TRUE(raised.islands.has_value());
  ASSERT_EQ(raised.islands->islands.size(), 1u);
  const double expected = std::pow(std::cos(1.2), 2) + std::pow(gain * std::sin(1.2), 2) - 1.0;
  EXPECT_NEAR(raised.islands->islands[0].max_energy_rise, expected, 1e-15);
  EXPECT_NEAR(expected, 2e-9, 1e-15);
  EXPECT_EQ(raised.islands->islands[0].worst_stamp_ns, 60 * kMs);
  const std::vector<std::string> failed = failed_checks(raised);
  ASSERT_EQ(failed.size(), 1u) << ::testing::PrintToString(failed);
  EXPECT_EQ(failed[0], "island energy rise: island of stones black_1, white_1");
}
