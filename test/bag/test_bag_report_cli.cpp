// Runs the real bag_report binary on generated bags and checks its output and exit code.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/bag_report_run.h"
#include "support/test_bags.h"

namespace {

using virtual_go_test::SyntheticRun;
using virtual_go_test::write_run_bag;

using Result = virtual_go_test::ReportRun;
using virtual_go_test::read_text;

std::string dir() {
  static const std::string d = [] {
    const std::string path = BAG_TEST_DIR;
    ::mkdir(path.c_str(), 0755);
    return path;
  }();
  return d;
}

Result run_report(const std::string& args) {
  return virtual_go_test::run_bag_report(BAG_REPORT_PATH, dir(), args);
}

std::size_t lines(const std::string& text) {
  std::size_t n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

// A failure is one line on stderr, never an abort or a stack trace.
void expect_clean_error(const Result& r) {
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.find("terminate"), std::string::npos) << r.err;
  EXPECT_LT(r.exit_code, 128) << "killed by a signal";
}

std::string bag(const std::string& name, const SyntheticRun& run) {
  const std::string path = dir() + "/" + name + ".bag";
  write_run_bag(path, run);
  return path;
}

TEST(BagReportCli, GoodRunPassesStrict) {
  const std::string path = bag("good", SyntheticRun{});
  const std::string csv = dir() + "/good.csv", png = dir() + "/good.png";
  std::remove(csv.c_str());
  std::remove(png.c_str());
  const Result r = run_report(path + " --strict --csv " + csv + " --plot " + png);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("result: ok"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("/stone/odom"), std::string::npos);
  EXPECT_NE(r.out.find("/tf world->stone"), std::string::npos);
  EXPECT_NE(r.out.find("start"), std::string::npos);  // the one segment
  EXPECT_EQ(r.out.find("FAIL"), std::string::npos) << r.out;
  // 2 s at 50 Hz: 101 odom rows plus the header.
  EXPECT_EQ(lines(read_text(csv)), 102u);
  const std::string png_bytes = read_text(png);
  ASSERT_GT(png_bytes.size(), 8u) << r.err;
  EXPECT_EQ(png_bytes.substr(1, 3), "PNG");
}

TEST(BagReportCli, GapAndDuplicatedStampAreReported) {
  SyntheticRun run;
  run.drop = {30, 31};   // a 60 ms step at 100.62 s
  run.duplicate = {50};  // 101.0 s twice
  const std::string path = bag("gap_dup", run);
  const Result r = run_report(path);
  EXPECT_EQ(r.exit_code, 0) << "without --strict the report itself succeeds\n" << r.err;
  EXPECT_NE(r.out.find("gap /stone/odom at 100.640000 s (step 60.000 ms"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("repeated stamp /stone/odom at 101.000000 s"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("repeated stamp /tf world->stone"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("FAIL  repeated stamps"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("FAIL  gaps > 2x period"), std::string::npos) << r.out;

  const Result strict = run_report(path + " --strict");
  EXPECT_EQ(strict.exit_code, 1);
  // A gap allowance lets the gap pass; the repeated stamp still fails.
  const Result lenient = run_report(path + " --strict --max-gaps 1");
  EXPECT_EQ(lenient.exit_code, 1);
  EXPECT_EQ(lenient.out.find("FAIL  gaps"), std::string::npos) << lenient.out;
}

TEST(BagReportCli, ResetEventRestartsThePrediction) {
  SyntheticRun run;
  run.reset_after = 1.0;
  const Result r = run_report(bag("reset", run) + " --strict");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("reset"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("2 segments"), std::string::npos) << r.out;

  // The same jump without its event is a real error, and is reported as one.
  run.reset_without_event = true;
  const Result hidden = run_report(bag("reset_no_event", run) + " --strict");
  EXPECT_EQ(hidden.exit_code, 1) << hidden.out;
  EXPECT_NE(hidden.out.find("FAIL  orientation error"), std::string::npos) << hidden.out;
}

// A bag of the StoneEvent version before stone names (no stone field): read as this version
// with empty names (the single stone), so its reset still starts the second segment.
TEST(BagReportCli, EventsRecordedBeforeStoneNamesAreRead) {
  SyntheticRun run;
  run.reset_after = 1.0;
  run.events_before_stone_names = true;
  const Result r = run_report(bag("events_before_names", run) + " --strict");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("2 segments"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("another message version"), std::string::npos) << r.out;
}

// A reason outside the name table has no rule to check its segment by: the event is skipped
// with a line naming the reason and the known ones, and the jump it hid fails --strict.
TEST(BagReportCli, UnknownEventReasonIsNamedAndSkipped) {
  SyntheticRun run;
  run.reset_after = 1.0;
  run.reset_reason = "teleport";
  const Result r = run_report(bag("unknown_reason", run) + " --strict");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE((r.out + r.err).find("unknown event reason 'teleport' (known: start reset auto_reset"),
            std::string::npos)
      << r.out << r.err;
  EXPECT_NE(r.out.find("FAIL  orientation error"), std::string::npos) << r.out;
}

TEST(BagReportCli, WithoutEventsOneSegmentFromTheFirstOdom) {
  SyntheticRun run;
  run.with_events = false;
  const Result r = run_report(bag("no_events", run) + " --strict");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("first odom"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1 segments"), std::string::npos) << r.out;
}

TEST(BagReportCli, OrientationErrorOverTheIntegratorBoundFails) {
  SyntheticRun run;
  run.orientation_drift_rate = 1e-6;  // 2e-6 rad after 2 s: far over exact's 1e-9
  const Result exact = run_report(bag("drift_exact", run) + " --strict");
  EXPECT_EQ(exact.exit_code, 1) << exact.out;
  EXPECT_NE(exact.out.find("FAIL  orientation error"), std::string::npos) << exact.out;
  // An explicit limit replaces the integrator's. (The drift leaves the body rates as they
  // were, so the reconstructed world L drifts too: that needs its own allowance.)
  const std::string allow_l = " --max-momentum-drift 1e-5";
  const Result loose =
      run_report(bag("drift_exact", run) + " --strict --max-orientation-error 1e-5" + allow_l);
  EXPECT_EQ(loose.exit_code, 0) << loose.out;
  // splitting at dt 1 ms and |w| ~ 25 rad/s allows about 2 (0.025)^2 25 * 2 = 6e-2 rad.
  run.integrator = "splitting";
  const Result splitting = run_report(bag("drift_splitting", run) + " --strict" + allow_l);
  EXPECT_EQ(splitting.exit_code, 0) << splitting.out;
}

TEST(BagReportCli, NonFiniteOdomSampleIsReportedAndTheRestGoesOn) {
  SyntheticRun run;
  run.nan_odom = {30};  // position x NaN at 100.6 s
  const std::string path = bag("nan_odom", run);
  const std::string csv = dir() + "/nan_odom.csv";
  const Result r = run_report(path + " --csv " + csv);
  EXPECT_EQ(r.exit_code, 0) << "without --strict the report itself succeeds\n" << r.err;
  EXPECT_NE(r.out.find("non-finite values      1 ~odom samples (first at 100.600000 s, position)"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("FAIL  non-finite values"), std::string::npos) << r.out;
  // The physics figures of every other sample are still there, and within the bounds.
  EXPECT_EQ(r.out.find("cannot describe"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ok    orientation error"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ok    energy drift"), std::string::npos) << r.out;
  EXPECT_EQ(lines(read_text(csv)), 102u);
  EXPECT_NE(read_text(csv).find("nan"), std::string::npos) << "the sample is marked NaN";

  const Result strict = run_report(path + " --strict");
  EXPECT_EQ(strict.exit_code, 1) << strict.out << strict.err;
}

TEST(BagReportCli, BagWithoutInfoIsAPartialReport) {
  SyntheticRun run;
  run.with_info = false;
  const Result r = run_report(bag("no_info", run));
  EXPECT_EQ(r.exit_code, 4) << r.out << r.err;
  EXPECT_NE(r.out.find("/stone/odom"), std::string::npos) << "topic figures still printed";
  EXPECT_NE(r.out.find("missing: no virtual_go/StoneInfo"), std::string::npos) << r.out;
  expect_clean_error(r);
}

TEST(BagReportCli, EmptyBag) {
  const std::string path = dir() + "/empty.bag";
  virtual_go_test::write_empty_bag(path);
  const Result r = run_report(path + " --strict");
  EXPECT_EQ(r.exit_code, 4) << r.out << r.err;
  EXPECT_NE(r.err.find("no messages"), std::string::npos) << r.err;
  expect_clean_error(r);
}

TEST(BagReportCli, TruncatedBag) {
  const std::string good = bag("to_truncate", SyntheticRun{});
  const std::string bytes = read_text(good);
  for (const double fraction : {0.9, 0.5, 0.1}) {
    const std::string path = dir() + "/truncated.bag";
    std::ofstream(path, std::ios::binary)
        << bytes.substr(0, static_cast<std::size_t>(bytes.size() * fraction));
    const Result r = run_report(path);
    EXPECT_EQ(r.exit_code, 3) << fraction << "\n" << r.out << r.err;
    EXPECT_NE(r.err.find("truncated.bag"), std::string::npos) << r.err;
    expect_clean_error(r);
  }
}

TEST(BagReportCli, CorruptChunkGivesAPartialReportOrAnError) {
  // Garbage in the middle of the data, index intact: either a clean error or a partial report.
  const std::string good = bag("to_corrupt", SyntheticRun{});
  std::string bytes = read_text(good);
  for (std::size_t i = bytes.size() / 3; i < bytes.size() / 3 + 2000; ++i) bytes[i] = '\x7f';
  const std::string path = dir() + "/corrupt.bag";
  std::ofstream(path, std::ios::binary) << bytes;
  const Result r = run_report(path);
  EXPECT_TRUE(r.exit_code == 3 || r.exit_code == 4 || r.exit_code == 0) << r.exit_code << r.err;
  EXPECT_LT(r.exit_code, 128) << "killed by a signal";
  EXPECT_LE(lines(r.err), 1u) << r.err;
}

// The line of the segments table for segment k ("  1  set_state ..."), or "".
std::string segment_line(const std::string& out, int k) {
  std::istringstream in(out);
  const std::string prefix = "  " + std::string(k < 10 ? "  " : " ") + std::to_string(k) + "  ";
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(prefix, 0) == 0) return line;
  }
  return "";
}

// issue 8: one event whose closed-form prediction overflows dropped the physics figures of the
// whole bag and blamed ~info. Now only its own segment has no prediction, named in a note.
TEST(BagReportCli, OverflowingEventAffectsOnlyItsOwnSegment) {
  SyntheticRun run;
  run.overflowing_event_after = 0.5;
  run.reset_after = 1.0;
  const std::string path = bag("overflowing_event", run);
  const Result r = run_report(path);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.out.find("cannot describe"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("3 segments"), std::string::npos) << r.out;
  const std::string before = segment_line(r.out, 0), bad = segment_line(r.out, 1),
                    after = segment_line(r.out, 2);
  EXPECT_NE(before.find("start"), std::string::npos) << r.out;
  EXPECT_EQ(before.find("n/a"), std::string::npos) << before;
  EXPECT_NE(bad.find("set_state"), std::string::npos) << r.out;
  EXPECT_NE(bad.find("n/a"), std::string::npos) << bad;
  EXPECT_NE(after.find("reset"), std::string::npos) << r.out;
  EXPECT_EQ(after.find("n/a"), std::string::npos) << after;
  EXPECT_NE(r.out.find("note: no prediction: the closed form from the set_state event at "
                       "100.500000000 s fails at t = "),
            std::string::npos)
      << r.out;
  // The segments before and after are held to their bounds as usual; --strict fails on the
  // figure that cannot be computed.
  const Result strict = run_report(path + " --strict");
  EXPECT_EQ(strict.exit_code, 1) << strict.out;
}

// Runs bag_report on `args` and returns its result with its peak resident memory (KiB).
Result run_report_measured(const std::vector<std::string>& args, long& peak_rss_kib) {
  const std::string out = dir() + "/stdout.txt", err = dir() + "/stderr.txt";
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(o, 1);
    ::dup2(e, 2);
    std::vector<char*> argv{const_cast<char*>(BAG_REPORT_PATH)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(BAG_REPORT_PATH, argv.data());
    ::_exit(127);
  }
  int status = 0;
  struct rusage usage {};
  ::wait4(pid, &status, 0, &usage);
  peak_rss_kib = usage.ru_maxrss;
  Result r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = read_text(out);
  r.err = read_text(err);
  return r;
}

// issue 8: one corrupt array length in a 90-byte /tf message made bag_report allocate 4.0 GB
// (30 million transforms declared) before giving up, and reading stopped there. The declared
// sizes are checked against the bytes first: the message is skipped and named, the rest of the
// bag is read, and the memory stays small.
TEST(BagReportCli, CorruptArrayLengthIsSkippedWithBoundedMemory) {
  const std::string good = bag("to_corrupt_length", SyntheticRun{});
  std::string bytes = read_text(good);
  // A /tf record: data length 90, then transforms[] length 1, header seq and stamp, then
  // frame_id "world" and child_frame_id "stone".
  const std::string frames = std::string("\x05\0\0\0world\x05\0\0\0stone", 18);
  const std::string tf_start = std::string("\x5a\0\0\0\x01\0\0\0", 8);
  std::size_t patched = 0, at = 0, seen = 0;
  while ((at = bytes.find(frames, at + 1)) != std::string::npos) {
    if (at < 20 || bytes.compare(at - 20, 8, tf_start) != 0) continue;  // odom, not tf
    if (++seen < 10) continue;                                          // the 10th /tf message
    const std::uint32_t declared = 30000000;
    std::memcpy(&bytes[at - 16], &declared, 4);
    patched = at;
    break;
  }
  ASSERT_NE(patched, 0u) << "no /tf message found in the bag";
  const std::string path = dir() + "/corrupt_length.bag";
  std::ofstream(path, std::ios::binary) << bytes;

  long peak_kib = 0;
  const Result r = run_report_measured({path}, peak_kib);
  EXPECT_LT(peak_kib, 256L * 1024) << "peak RSS " << peak_kib / 1024 << " MiB";
  EXPECT_EQ(r.exit_code, 4) << "a partial report: one message is missing\n" << r.out << r.err;
  EXPECT_NE(r.out.find("/tf at 100.180000000 s, 90 bytes) is corrupt and was skipped: an array "
                       "declares 30000000 elements of at least"),
            std::string::npos)
      << r.out;
  // The rest was read: all 101 transforms but one, and the physics of every odom sample.
  const std::size_t tf_row = r.out.find("  /tf world->stone ");
  ASSERT_NE(tf_row, std::string::npos) << r.out;
  std::istringstream row(r.out.substr(tf_row));
  std::string topic, pair;
  std::size_t count = 0;
  row >> topic >> pair >> count;
  EXPECT_EQ(count, 100u) << r.out;
  EXPECT_NE(r.out.find("/stone/odom, 101 samples"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("reading stopped"), std::string::npos) << r.out;
  expect_clean_error(r);
}

TEST(BagReportCli, MissingFileAndNotABag) {
  const Result missing = run_report(dir() + "/does_not_exist.bag");
  EXPECT_EQ(missing.exit_code, 3);
  EXPECT_NE(missing.err.find("no such file"), std::string::npos) << missing.err;
  expect_clean_error(missing);

  const std::string text = dir() + "/not_a_bag.bag";
  std::ofstream(text) << "hello, I am not a bag\n";
  const Result not_bag = run_report(text);
  EXPECT_EQ(not_bag.exit_code, 3);
  expect_clean_error(not_bag);
}

TEST(BagReportCli, UsageAndHelp) {
  const Result help = run_report("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.out.find("exit codes"), std::string::npos);
  const Result none = run_report("");
  EXPECT_EQ(none.exit_code, 2);
  expect_clean_error(none);
  const Result bad = run_report("x.bag --max-gaps lots");
  EXPECT_EQ(bad.exit_code, 2);
  expect_clean_error(bad);
  const Result unknown = run_report("x.bag --frobnicate");
  EXPECT_EQ(unknown.exit_code, 2);
  expect_clean_error(unknown);
}

TEST(BagReportCli, UnwritableOutput) {
  const Result r = run_report(bag("good_out", SyntheticRun{}) + " --csv /nonexistent/dir/x.csv");
  EXPECT_EQ(r.exit_code, 5);
  expect_clean_error(r);
}

TEST(BagReportCli, TopicsFoundByTypeUnderAnotherNamespace) {
  // No /other/odom etc.: the unique topics of each type are used.
  const Result r = run_report(bag("good_ns", SyntheticRun{}) + " --strict --node-namespace /other");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
}

}  // namespace
