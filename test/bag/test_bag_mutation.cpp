// issue 19: bag_report on bags damaged byte by byte. rosbag trusts the lengths and offsets in
// the file; one flipped byte in an index entry made it read outside its chunk (SIGSEGV). Every
// damaged bag must end in a report or a one-line error, never a signal or an endless run.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "support/bag_report_run.h"
#include "support/test_bags.h"

namespace {

using virtual_go_test::read_text;
using virtual_go_test::ReportRun;

std::string dir() {
  static const std::string d = [] {
    const std::string path = BAG_TEST_DIR;
    ::mkdir(path.c_str(), 0755);
    return path;
  }();
  return d;
}

// A guard against an endless run only (a report of this bag takes well under a second).
ReportRun run_report(const std::string& bag) {
  return virtual_go_test::run_bag_report("timeout -s KILL 60 " BAG_REPORT_PATH, dir(), bag);
}

std::size_t lines(const std::string& text) {
  std::size_t n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

std::uint32_t u32_at(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, bytes.data() + at, 4);
  return v;
}

// The top-level records of a rosbag 2.0 file, read here from the format's description
// (wiki.ros.org/Bags/Format/2.0), not with the code under test: where each starts, its header
// and its data.
struct RecordSpan {
  std::size_t pos, header_pos, header_len, data_pos, data_len;
  std::uint8_t op;
};

std::vector<RecordSpan> top_level_records(const std::string& bytes) {
  std::vector<RecordSpan> out;
  std::size_t at = 13;  // after "#ROSBAG V2.0\n"
  while (at + 8 <= bytes.size()) {
    RecordSpan r{};
    r.pos = at;
    r.header_len = u32_at(bytes, at);
    r.header_pos = at + 4;
    r.data_len = u32_at(bytes, r.header_pos + r.header_len);
    r.data_pos = r.header_pos + r.header_len + 4;
    const std::size_t op = bytes.find(std::string("op=", 3), r.header_pos);
    r.op = static_cast<std::uint8_t>(bytes[op + 3]);
    out.push_back(r);
    at = r.data_pos + r.data_len;
  }
  return out;
}

const std::string& good_bag_bytes() {
  static const std::string bytes = [] {
    const std::string path = dir() + "/to_mutate.bag";
    virtual_go_test::write_run_bag(path, virtual_go_test::SyntheticRun{});
    return read_text(path);
  }();
  return bytes;
}

std::string write_bag(const std::string& name, const std::string& bytes) {
  const std::string path = dir() + "/" + name + ".bag";
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// What every damaged bag must give: a report (0, or 4 when partial) or a clean refusal (3), one
// line on stderr at most, no signal, no uncaught exception.
void expect_handled(const ReportRun& r, const std::string& what) {
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 3 || r.exit_code == 4)
      << what << ": exit " << r.exit_code << (r.exit_code >= 128 ? " (a signal)" : "") << "\n"
      << r.err;
  EXPECT_LE(lines(r.err), 1u) << what << "\n" << r.err;
  EXPECT_EQ(r.err.find("unexpected error"), std::string::npos) << what << "\n" << r.err;
  EXPECT_EQ(r.err.find("terminate"), std::string::npos) << what << "\n" << r.err;
}

// The reproduction of issue 19: the top byte of the first index entry's offset (byte 11 of the
// first IndexData record's data) set, so the entry points 2^24 bytes and more past its chunk.
TEST(BagMutation, IndexEntryOffsetPastItsChunkIsSkippedAndNamed) {
  std::string bytes = good_bag_bytes();
  const std::vector<RecordSpan> records = top_level_records(bytes);
  const RecordSpan* index = nullptr;
  for (const RecordSpan& r : records) {
    if (r.op == 4) {
      index = &r;
      break;
    }
  }
  ASSERT_NE(index, nullptr);
  ASSERT_GE(index->data_len, 12u);
  const ReportRun good = run_report(write_bag("unmutated", bytes));
  ASSERT_EQ(good.exit_code, 0) << good.out << good.err;

  bytes[index->data_pos + 11] = '\x5a';
  const ReportRun r = run_report(write_bag("index_offset", bytes));
  EXPECT_EQ(r.exit_code, 4) << "a partial report\n" << r.out << r.err;
  EXPECT_NE(r.out.find("an index entry points at no message and was skipped: entry 1 of the "
                       "index record at byte " +
                       std::to_string(index->pos)),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("leaves no record in the chunk's"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1 index entries point at no message (1 messages skipped)"),
            std::string::npos)
      << r.out;
  expect_handled(r, "index offset");
}

// Damage to the records rosbag reads before any message: a clear refusal naming the record.
TEST(BagMutation, DamagedIndexRecordsAreRefusedByName) {
  const std::string good = good_bag_bytes();
  const std::vector<RecordSpan> records = top_level_records(good);
  const RecordSpan* chunk_info = nullptr;
  const RecordSpan* index = nullptr;
  for (const RecordSpan& r : records) {
    if (r.op == 6 && !chunk_info) chunk_info = &r;
    if (r.op == 4 && !index) index = &r;
  }
  ASSERT_NE(chunk_info, nullptr);
  ASSERT_NE(index, nullptr);

  // The chunk info's data holds count pairs (connection, messages): a count of 2^31 pairs
  // cannot fit its data, and rosbag would read on through the file.
  std::string bytes = good;
  const std::size_t count = bytes.find(std::string("\x0a\0\0\0count=", 10), chunk_info->header_pos);
  ASSERT_NE(count, std::string::npos);
  bytes[count + 13] = '\x7f';
  ReportRun r = run_report(write_bag("chunk_info_count", bytes));
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_NE(r.err.find("is corrupt: the chunk info 1 of 1 record at byte " +
                       std::to_string(chunk_info->pos) + " lists 2130706437 connections in"),
            std::string::npos)
      << r.err;
  expect_handled(r, "chunk info count");

  // An index record's header length past the end of the file.
  bytes = good;
  bytes[index->pos + 3] = '\x40';
  r = run_report(write_bag("index_header_length", bytes));
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_NE(r.err.find("the header of the index record at byte " + std::to_string(index->pos)),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("runs past the end of the file"), std::string::npos) << r.err;
  expect_handled(r, "index header length");
}

// Seeded fuzz: damaged copies of one recorded bag, each damaged in one of several ways, a third
// of them aimed at the index (the records after the chunk data), where one byte moves what
// rosbag reads. The count is BAG_MUTATIONS (test/bag_tests.cmake); issue 19's done-when figure,
// 1,000 bags with 0 crashes, was measured with this test.
TEST(BagMutation, SeededMutationsNeverCrash) {
  const std::string good = good_bag_bytes();
  const std::vector<RecordSpan> records = top_level_records(good);
  std::size_t index_start = good.size();
  for (const RecordSpan& r : records) {
    if (r.op == 4) index_start = std::min(index_start, r.pos);
  }
  ASSERT_LT(index_start, good.size());

  std::mt19937_64 rng(19);
  const int kBags = BAG_MUTATIONS;
  int refused = 0, partial = 0, full = 0;
  for (int i = 0; i < kBags; ++i) {
    std::string bytes = good;
    auto pick = [&](std::size_t lo, std::size_t hi) {  // in [lo, hi)
      return std::uniform_int_distribution<std::size_t>(lo, hi - 1)(rng);
    };
    const std::size_t lo = pick(0, 3) == 0 ? index_start : 0;  // a third aimed at the index
    const int kind = static_cast<int>(pick(0, 6));
    std::string what = "bag " + std::to_string(i) + " kind " + std::to_string(kind);
    switch (kind) {
      case 0:  // one bit
        bytes[pick(lo, bytes.size())] ^= static_cast<char>(1 << pick(0, 8));
        break;
      case 1:  // one byte
        bytes[pick(lo, bytes.size())] = static_cast<char>(pick(0, 256));
        break;
      case 2: {  // a 32-bit word set to an extreme
        const std::uint32_t values[] = {
            0u, 1u, 0x7fffffffu, 0xffffffffu, 0x01000000u, static_cast<std::uint32_t>(rng())};
        const std::uint32_t v = values[pick(0, 6)];
        std::memcpy(&bytes[pick(lo, bytes.size() - 4)], &v, 4);
        break;
      }
      case 3:  // truncated
        bytes.resize(pick(lo, bytes.size()));
        break;
      case 4:  // bytes removed (what follows moves)
        bytes.erase(pick(lo, bytes.size() - 64), pick(1, 64));
        break;
      case 5: {  // bytes repeated
        const std::size_t at = pick(lo, bytes.size() - 64);
        bytes.insert(at, bytes.substr(at, pick(1, 64)));
        break;
      }
    }
    const ReportRun r = run_report(write_bag("mutated", bytes));
    expect_handled(r, what);
    if (r.exit_code == 3) ++refused;
    if (r.exit_code == 4) ++partial;
    if (r.exit_code == 0) ++full;
    if (r.exit_code >= 128 || r.exit_code == 1 || r.exit_code == 2) {
      write_bag("crash_" + std::to_string(i), bytes);  // kept for a look
    }
  }
  std::printf("%d mutated bags: %d refused, %d partial reports, %d full reports\n", kBags, refused,
              partial, full);
  EXPECT_EQ(refused + partial + full, kBags);
}

}  // namespace
