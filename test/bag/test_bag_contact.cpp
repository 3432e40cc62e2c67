// bag_report's contact checks on bags of the core's World (support/world_bags.h): a flat drop, a
// tilted spinning toss that lands, slides, rocks and rests, a stone placed at rest, and a toss
// without rolling resistance or spinning friction (Jellett's integral held in contact) pass
// --strict; copies with one sample corrupted (energy raised above the sample before, pushed 1e-6 m
// into the board, a resting sample moved by one ulp, a flight sample rotated by 1e-6 rad) fail it,
// naming the check that caught them; a bag of an older StoneInfo says so.
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <virtual_go/StoneInfo.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "support/bag_report_run.h"
#include "support/world_bags.h"
#include "virtual_go/bag/bag_reader.h"
#include "virtual_go/bag/report.h"
#include "virtual_go/go/stone.h"

namespace {

namespace vb = virtual_go::bag;
using virtual_go_test::Corruption;
using virtual_go_test::WorldRunSpec;
using virtual_go_test::WorldRunSummary;

using Result = virtual_go_test::ReportRun;
using virtual_go_test::read_text;

std::string dir() {
  static const std::string d = [] {
    const std::string path = std::string(BAG_TEST_DIR) + "_contact";
    ::mkdir(path.c_str(), 0755);
    return path;
  }();
  return d;
}

Result run_report(const std::string& args) {
  return virtual_go_test::run_bag_report(BAG_REPORT_PATH, dir(), args);
}

double half_height() { return virtual_go::make_stone(virtual_go::StoneSpec{}).shape.half_height(); }

virtual_go::RigidBodyState flat_at(double z) {
  virtual_go::RigidBodyState s;
  s.position_world = Eigen::Vector3d(0.01, -0.02, z);
  return s;
}

// The tilted spinning toss of the World's tests: lands, bounces, slides, rocks, rests (~21 s).
virtual_go::RigidBodyState tilted_toss() {
  const virtual_go::Stone stone = virtual_go::make_stone(virtual_go::StoneSpec{});
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1, 0).normalized()));
  virtual_go::RigidBodyState s;
  s.position_world = Eigen::Vector3d(0, 0, 0.03);
  s.orientation = q;
  s.velocity_world = Eigen::Vector3d(0.2, 0.05, 0);
  const Eigen::Vector3d omega = q * Eigen::Vector3d(0, 0, 10.0) + Eigen::Vector3d(1, -2, 0);
  const Eigen::Matrix3d r = q.toRotationMatrix();
  s.angular_momentum_world =
      r * stone.mass_properties.principal_moments_body().asDiagonal() * r.transpose() * omega;
  return s;
}

WorldRunSpec drop_spec() {
  WorldRunSpec spec;
  spec.initial = flat_at(half_height() + 0.05);
  spec.duration_s = 0.6;
  return spec;
}

WorldRunSpec toss_spec() {
  WorldRunSpec spec;
  spec.initial = tilted_toss();
  spec.duration_s = 23.0;
  spec.dt_ns = 5'000'000;
  return spec;
}

WorldRunSpec rest_spec() {
  WorldRunSpec spec;
  spec.initial = flat_at(half_height());
  spec.duration_s = 0.5;
  return spec;
}

std::string write(const std::string& name, const WorldRunSpec& spec, WorldRunSummary* summary) {
  const std::string path = dir() + "/" + name + ".bag";
  *summary = virtual_go_test::write_world_bag(path, spec);
  return path;
}

// The check row of `figure` that failed: "  FAIL  <figure>".
bool failed(const Result& r, const std::string& figure) {
  return r.out.find("FAIL  " + figure) != std::string::npos;
}

TEST(BagContact, FlatDropPassesStrict) {
  WorldRunSummary s;
  const std::string bag = write("drop", drop_spec(), &s);
  EXPECT_GE(s.impacts, 7u);  // e* 0.5 from 5 cm: 7 bounces above the 1 um cut-off
  EXPECT_EQ(s.rests, 1u);    // the last impact leaves a flat stone at rest at once
  const Result r = run_report(bag + " --strict");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("impact"), std::string::npos);
  EXPECT_NE(r.out.find("rest (rest"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ok    penetration (m)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ok    rest motion"), std::string::npos) << r.out;
}

TEST(BagContact, TossThatSlidesRocksAndRestsPassesStrict) {
  WorldRunSummary s;
  const std::string bag = write("toss", toss_spec(), &s);
  EXPECT_GE(s.impacts, 2u);
  EXPECT_GE(s.contacts, 2u);
  ASSERT_EQ(s.rests, 1u);
  EXPECT_LT(s.rest_time_s, toss_spec().duration_s - 0.5);  // rested, then sampled still
  const Result r = run_report(bag + " --strict");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("slide (contact"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ok    energy rise"), std::string::npos) << r.out;
  std::printf("%s", r.out.substr(r.out.find("physics (")).c_str());
}

TEST(BagContact, StonePlacedAtRestPassesStrict) {
  WorldRunSummary s;
  const std::string bag = write("rest", rest_spec(), &s);
  ASSERT_EQ(s.rests, 1u);
  EXPECT_EQ(s.rest_time_s, 0.0);
  const Result r = run_report(bag + " --strict");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("rest samples moved     0"), std::string::npos) << r.out;
}

// Edges: a flat stone placed level with the board's top, its centre 1 mm beyond the top edge,
// drops the 32 um onto the edge, pivots over it in the World's fallback (edge_contact) and falls
// onto the table; one sliding fast towards the side leaves the board and lands on the table.
// Both pass: no sample's energy lies above an earlier one in contact, and no sample lies below
// the board or the table.
TEST(BagContact, EdgeLandingAndSlidingOffOntoTheTablePassStrict) {
  const double half_x = 0.4242 / 2;
  WorldRunSpec edge;
  edge.initial = flat_at(half_height());
  edge.initial.position_world.x() = half_x + 0.001;
  edge.duration_s = 1.5;
  WorldRunSummary s;
  const std::string edge_bag = write("edge", edge, &s);
  EXPECT_GE(s.impacts, 1u);
  const Result r = run_report(edge_bag + " --strict");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("edge_contact"), std::string::npos) << r.out;  // the fallback ran
  std::printf("%s", r.out.substr(r.out.find("segments (")).c_str());

  WorldRunSpec off;
  off.initial = flat_at(half_height());  // placed on the board, sliding: 0.17 m to stop
  off.initial.position_world.x() = half_x - 0.05;
  off.initial.velocity_world = Eigen::Vector3d(1.0, 0.0, 0.0);
  off.duration_s = 1.5;
  const std::string off_bag = write("slide_off", off, &s);
  const Result r2 = run_report(off_bag + " --strict");
  EXPECT_EQ(r2.exit_code, 0) << r2.out << r2.err;
  EXPECT_NE(r2.out.find("left_region"), std::string::npos) << r2.out;  // slid off the top face
}

// Without rolling resistance and spinning friction Jellett's integral holds in sliding and
// rolling on a cap: the contact segments are held to it too.
TEST(BagContact, JellettsIntegralIsCheckedInContactWithoutRollingResistance) {
  WorldRunSpec spec = toss_spec();
  spec.duration_s = 1.5;
  spec.material.rolling_resistance_m = 0.0;
  spec.material.spinning_friction_m = 0.0;
  WorldRunSummary s;
  const std::string bag = write("jellett", spec, &s);
  const vb::Report report = vb::analyse(vb::read_recording(bag, "/stone"), vb::LimitOverrides{});
  ASSERT_TRUE(report.physics);
  std::size_t checked_contact = 0;
  double worst = 0.0;
  for (const vb::SegmentResult& seg : report.physics->segments) {
    if (seg.kind == vb::SegmentKind::contact && seg.jellett_conserved && seg.samples > 2) {
      ++checked_contact;
      worst = std::max(worst, seg.max_jellett_drift);
    }
  }
  EXPECT_GE(checked_contact, 1u);
  EXPECT_LE(worst, vb::contact_limit(vb::kJellettDrift).default_limit);
  EXPECT_TRUE(report.checks_pass());
  std::printf("[ jellett ] %zu contact segments held to Jellett's integral, worst drift %.2e\n",
              checked_contact, worst);
  // With the default rolling resistance it is not conserved in contact, and not checked there.
  spec.material = virtual_go::ContactMaterial{};
  const std::string resisted = write("jellett_resisted", spec, &s);
  const vb::Report r2 = vb::analyse(vb::read_recording(resisted, "/stone"), vb::LimitOverrides{});
  ASSERT_TRUE(r2.physics);
  for (const vb::SegmentResult& seg : r2.physics->segments) {
    if (seg.kind == vb::SegmentKind::contact) {
      EXPECT_FALSE(seg.jellett_conserved);
    }
    if (seg.kind == vb::SegmentKind::flight && seg.samples > 0) {
      EXPECT_TRUE(seg.jellett_conserved);
    }
  }
}

struct CorruptCase {
  const char* name;
  Corruption corruption;
  WorldRunSpec (*spec)();
  const char* figure;  // the check that must fail
};

class BagContactCorrupt : public ::testing::TestWithParam<CorruptCase> {};

TEST_P(BagContactCorrupt, FailsStrictNamingTheCheck) {
  const CorruptCase& c = GetParam();
  WorldRunSpec spec = c.spec();
  spec.corruption = c.corruption;
  WorldRunSummary s;
  const std::string bag = write(std::string("corrupt_") + c.name, spec, &s);
  ASSERT_TRUE(s.corrupted) << "no sample to corrupt";
  const Result r = run_report(bag + " --strict");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_TRUE(failed(r, c.figure)) << c.figure << "\n" << r.out;
  // Without --strict the same report, exit 0.
  EXPECT_EQ(run_report(bag).exit_code, 0);
}

INSTANTIATE_TEST_SUITE_P(
    Corruptions, BagContactCorrupt,
    ::testing::Values(
        CorruptCase{"energy", Corruption::energy_bump, toss_spec, "energy rise"},
        CorruptCase{"pushed", Corruption::pushed_into_board, toss_spec, "penetration (m)"},
        CorruptCase{"rest_ulp", Corruption::rest_ulp, rest_spec, "rest motion"},
        CorruptCase{"flight", Corruption::flight_rotation, drop_spec, "orientation error (rad)"}),
    [](const ::testing::TestParamInfo<CorruptCase>& info) { return std::string(info.param.name); });

// A bag whose ~info is another version of StoneInfo (another md5sum, as every bag recorded before
// the board was added) is named as such, not read as garbage.
TEST(BagContact, OlderStoneInfoIsNamed) {
  WorldRunSummary s;
  const std::string good = write("old_source", rest_spec(), &s);
  const std::string old = dir() + "/old_info.bag";
  {
    rosbag::Bag in(good, rosbag::bagmode::Read);
    rosbag::Bag out(old, rosbag::bagmode::Write);
    for (const rosbag::MessageInstance& m : rosbag::View(in)) {
      if (m.getTopic() == "/stone/info") {
        auto header = boost::make_shared<ros::M_string>(*m.getConnectionHeader());
        (*header)["md5sum"] = "0123456789abcdef0123456789abcdef";
        out.write(m.getTopic(), m.getTime(), m, header);
      } else {
        out.write(m.getTopic(), m.getTime(), m, m.getConnectionHeader());
      }
    }
  }
  const Result r = run_report(old + " --strict");
  EXPECT_EQ(r.exit_code, 4) << r.out << r.err;
  EXPECT_NE(r.out.find("another message version"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("older virtual_go"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("no virtual_go/StoneInfo message"), std::string::npos) << r.out;
}

}  // namespace
