// Checks a rosbag (format 2.0) record by record against the file before rosbag reads it.
// rosbag trusts the lengths, offsets and counts it finds: an index entry whose offset points
// past its chunk makes it read outside its buffer (issue 19: SIGSEGV on one flipped byte).
// Everything rosbag will read is checked here first, the way rosbag reads it.
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace virtual_go {
namespace bag {

struct BagStructure {
  // Messages the index lists whose record is not a whole message inside its chunk, by topic and
  // receipt time (ns): rosbag must not be asked for them (one key may cover a good message of
  // the same topic and time too; it is skipped with the bad one).
  std::set<std::pair<std::string, std::int64_t>> bad_messages;
  std::size_t bad_entry_count = 0;
  // Why, for the first few bad entries (one line each, naming the byte offsets).
  std::vector<std::string> bad_entry_reasons;
};

// Throws BagReadError (bag_reader.h) naming the first record that does not fit the file: the
// version line, the file header, a connection, chunk info, chunk or index record (a length,
// count or position past the file, a missing or wrong-sized field). Entries of intact index
// records that point at no message are returned instead, so the rest of the bag can be read.
// Memory: one chunk at a time; a compressed chunk may declare at most kMaxChunkBytes.
BagStructure check_bag_structure(const std::string& path);

constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{1} << 30;

}  // namespace bag
}  // namespace virtual_go
