#include "virtual_go/bag/bag_structure.h"

#include <rosbag/chunked_file.h>
#include <rosbag/exceptions.h>

#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include "virtual_go/bag/bag_reader.h"

namespace virtual_go {
namespace bag {
namespace {

// Record ops of the format (http://wiki.ros.org/Bags/Format/2.0).
constexpr std::uint8_t kOpMessageDefinition = 0x01;  // format 1.2, skipped by rosbag in chunks
constexpr std::uint8_t kOpMessageData = 0x02;
constexpr std::uint8_t kOpFileHeader = 0x03;
constexpr std::uint8_t kOpIndexData = 0x04;
constexpr std::uint8_t kOpChunk = 0x05;
constexpr std::uint8_t kOpChunkInfo = 0x06;
constexpr std::uint8_t kOpConnection = 0x07;
constexpr char kVersionLine[] = "#ROSBAG V2.0\n";
// ros::Header::parse refuses longer fields (and reads them without checking the header's end).
constexpr std::uint32_t kMaxFieldBytes = 1000000;
// Bad entries named one by one; the rest are counted.
constexpr std::size_t kBadEntriesNamed = 5;

std::uint32_t u32_at(const char* p) {
  std::uint32_t v = 0;  // the format is little-endian, as the hosts ROS 1 runs on
  std::memcpy(&v, p, 4);
  return v;
}

using Fields = std::map<std::string, std::string>;

// A record header's fields, as ros::Header::parse reads them (a later duplicate wins), but
// every length checked against the header's end first. Empty reason: parsed.
std::string parse_fields(const char* p, std::uint64_t size, Fields& out) {
  std::uint64_t at = 0;
  while (at < size) {
    if (size - at < 4) return "a field length is cut off by the header's end";
    const std::uint32_t len = u32_at(p + at);
    at += 4;
    if (len > kMaxFieldBytes) return "a field declares " + std::to_string(len) + " bytes";
    if (len > size - at) {
      return "a field of " + std::to_string(len) + " bytes runs past the header's end";
    }
    const std::string line(p + at, len);
    at += len;
    const std::size_t eq = line.find('=');
    if (eq == std::string::npos) return "a field has no '='";
    out[line.substr(0, eq)] = line.substr(eq + 1);
  }
  return "";
}

// The bag file, read at explicit positions; every read is checked against its size.
class BagFile {
 public:
  explicit BagFile(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) throw BagReadError("cannot open " + path);
    in_.seekg(0, std::ios::end);
    size_ = static_cast<std::uint64_t>(in_.tellg());
  }

  std::uint64_t size() const { return size_; }

  [[noreturn]] void fail(const std::string& what) const {
    throw BagReadError(path_ + " is corrupt: " + what + " (the file has " + std::to_string(size_) +
                       " bytes)");
  }

  // n bytes at pos; `what` names them in the error when they are not all in the file.
  std::string read(std::uint64_t pos, std::uint64_t n, const std::string& what) {
    if (pos > size_ || n > size_ - pos) {
      fail(what + " at byte " + std::to_string(pos) + " (" + std::to_string(n) +
           " bytes) runs past the end of the file");
    }
    std::string bytes(n, '\0');
    in_.seekg(static_cast<std::streamoff>(pos));
    in_.read(bytes.data(), static_cast<std::streamsize>(n));
    if (!in_) fail("cannot read " + what + " at byte " + std::to_string(pos));
    return bytes;
  }

 private:
  std::string path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
};

// One record: <header_len><header><data_len><data>.
struct Record {
  std::uint64_t pos = 0;
  Fields fields;
  std::uint64_t data_pos = 0;
  std::uint32_t data_len = 0;
  std::string what;  // "chunk info 1 of 3 (the record at byte 1234)"
};

Record read_record(BagFile& file, std::uint64_t pos, const std::string& kind) {
  Record r;
  r.pos = pos;
  r.what = kind + " record at byte " + std::to_string(pos);  // kind: "index", "chunk info 1 of 3"
  const std::uint32_t header_len =
      u32_at(file.read(pos, 4, "the header length of the " + r.what).data());
  const std::string header = file.read(pos + 4, header_len, "the header of the " + r.what);
  const std::string why = parse_fields(header.data(), header.size(), r.fields);
  if (!why.empty()) file.fail("the header of the " + r.what + ": " + why);
  r.data_pos = pos + 8 + header_len;
  r.data_len =
      u32_at(file.read(pos + 4 + header_len, 4, "the data length of the " + r.what).data());
  return r;
}

// A field of exactly n bytes (rosbag's readField refuses other sizes).
const std::string& field(BagFile& file, const Record& r, const std::string& name, std::size_t n) {
  const auto it = r.fields.find(name);
  if (it == r.fields.end()) file.fail("the " + r.what + " has no '" + name + "' field");
  if (n != 0 && it->second.size() != n) {
    file.fail("the " + r.what + "'s '" + name + "' field has " + std::to_string(it->second.size()) +
              " bytes, expected " + std::to_string(n));
  }
  return it->second;
}

std::uint32_t field_u32(BagFile& file, const Record& r, const std::string& name) {
  return u32_at(field(file, r, name, 4).data());
}

std::uint64_t field_u64(BagFile& file, const Record& r, const std::string& name) {
  std::uint64_t v = 0;
  std::memcpy(&v, field(file, r, name, 8).data(), 8);
  return v;
}

void expect_op(BagFile& file, const Record& r, std::uint8_t op) {
  const std::uint8_t got = static_cast<std::uint8_t>(field(file, r, "op", 1)[0]);
  if (got != op) {
    file.fail("the " + r.what + " has op " + std::to_string(got) + ", expected " +
              std::to_string(op));
  }
}

struct Chunk {
  std::uint64_t pos = 0;
  std::string compression;
  std::uint32_t size = 0;  // uncompressed
  std::uint64_t data_pos = 0;
  std::uint32_t data_len = 0;
};

Chunk read_chunk_header(BagFile& file, std::uint64_t pos, const std::string& from) {
  Record r = read_record(file, pos, "chunk");
  r.what += " (named by the " + from + ")";
  expect_op(file, r, kOpChunk);
  Chunk c;
  c.pos = pos;
  c.compression = field(file, r, "compression", 0);
  c.size = field_u32(file, r, "size");
  c.data_pos = r.data_pos;
  c.data_len = r.data_len;
  file.read(c.data_pos + c.data_len, 0, "the end of the " + r.what);
  if (c.compression == "none" && c.size != c.data_len) {
    file.fail("the " + r.what + " is uncompressed but declares " + std::to_string(c.size) +
              " bytes and holds " + std::to_string(c.data_len));
  }
  if (c.compression != "none" && c.compression != "bz2" && c.compression != "lz4") {
    file.fail("the " + r.what + " has an unknown compression '" + c.compression + "'");
  }
  if (c.size > kMaxChunkBytes) {
    file.fail("the " + r.what + " declares " + std::to_string(c.size) +
              " uncompressed bytes, over bag_report's limit of " + std::to_string(kMaxChunkBytes));
  }
  return c;
}

// The chunk's bytes as rosbag holds them when it reads a message: for a compressed chunk,
// decompressed by rosbag's own code. Empty reason: ok.
std::string chunk_bytes(BagFile& file, const Chunk& c, std::string& out) {
  const std::string stored = file.read(c.data_pos, c.data_len, "the data of the chunk");
  if (c.compression == "none") {
    out = stored;
    return "";
  }
  const rosbag::CompressionType type =
      c.compression == "bz2" ? rosbag::compression::BZ2 : rosbag::compression::LZ4;
  // rosbag decompresses into a buffer of the declared size and does not say how much it wrote:
  // two fills that still differ afterwards show a short output (rosbag would read stale bytes).
  std::string zeros(c.size, '\0'), ones(c.size, '\xff');
  try {
    rosbag::ChunkedFile codec;
    std::string in = stored;
    codec.decompress(type, reinterpret_cast<std::uint8_t*>(zeros.data()), c.size,
                     reinterpret_cast<std::uint8_t*>(in.data()), c.data_len);
    in = stored;
    codec.decompress(type, reinterpret_cast<std::uint8_t*>(ones.data()), c.size,
                     reinterpret_cast<std::uint8_t*>(in.data()), c.data_len);
  } catch (const std::exception& e) {
    return std::string("it cannot be decompressed: ") + e.what();
  }
  if (zeros != ones) return "it decompresses to fewer than the declared bytes";
  out = std::move(zeros);
  return "";
}

// Why the record at `offset` of a chunk's bytes is not a whole message, as rosbag reads it
// (readMessageDataHeaderFromBuffer: connection records before it are skipped); "" when it is.
std::string message_problem(const std::string& chunk, std::uint32_t offset) {
  const std::uint64_t size = chunk.size();
  if (size <= 8) return "the chunk holds only " + std::to_string(size) + " bytes";
  std::uint64_t at = offset;
  for (;;) {  // each turn moves at least 8 bytes on: at most size / 8 turns
    if (at > size || size - at < 8) {
      return "offset " + std::to_string(at) + " leaves no record in the chunk's " +
             std::to_string(size) + " bytes";
    }
    const std::uint32_t header_len = u32_at(chunk.data() + at);
    if (header_len > size - at - 8) {
      return "the record at offset " + std::to_string(at) + " declares a " +
             std::to_string(header_len) + "-byte header, past the chunk's " + std::to_string(size) +
             " bytes";
    }
    Fields fields;
    const std::string why = parse_fields(chunk.data() + at + 4, header_len, fields);
    if (!why.empty()) return "the record at offset " + std::to_string(at) + ": " + why;
    const auto op = fields.find("op");
    if (op == fields.end() || op->second.size() != 1) {
      return "the record at offset " + std::to_string(at) + " has no one-byte op";
    }
    const std::uint32_t data_len = u32_at(chunk.data() + at + 4 + header_len);
    const std::uint64_t data_pos = at + 8 + header_len;
    const auto kind = static_cast<std::uint8_t>(op->second[0]);
    if (kind == kOpConnection || kind == kOpMessageDefinition) {
      at = data_pos;  // rosbag steps over the header only
      continue;
    }
    if (kind != kOpMessageData) {
      return "the record at offset " + std::to_string(at) + " has op " + std::to_string(kind) +
             ", not a message";
    }
    if (data_len > size - data_pos) {
      return "the message at offset " + std::to_string(at) + " declares " +
             std::to_string(data_len) + " bytes, past the chunk's " + std::to_string(size);
    }
    return "";
  }
}

}  // namespace

BagStructure check_bag_structure(const std::string& path) {
  BagFile file(path);
  const std::size_t version_len = std::strlen(kVersionLine);
  if (file.size() < version_len || file.read(0, version_len, "the version line") != kVersionLine) {
    throw BagReadError(path +
                       " does not start with \"#ROSBAG V2.0\": not a rosbag of format "
                       "2.0 (the only one bag_report reads)");
  }

  const Record header = read_record(file, version_len, "file header");
  expect_op(file, header, kOpFileHeader);
  const std::uint64_t index_pos = field_u64(file, header, "index_pos");
  if (index_pos == 0) {
    throw BagReadError(path + " has no index (recording interrupted?); `rosbag reindex " + path +
                       "` may recover it");
  }
  const std::uint32_t connection_count = field_u32(file, header, "conn_count");
  const std::uint32_t chunk_count = field_u32(file, header, "chunk_count");
  const auto encryptor = header.fields.find("encryptor");
  if (encryptor != header.fields.end() && !encryptor->second.empty() &&
      encryptor->second != "rosbag/NoEncryptor") {
    file.fail("the bag is encrypted with '" + encryptor->second +
              "', which bag_report does not read");
  }
  file.read(header.data_pos, header.data_len, "the padding of the " + header.what);

  // Connections, then chunk infos, read back to back from index_pos: a record's count, not its
  // data length, says where rosbag reads the next one, so the two must agree.
  std::map<std::uint32_t, std::string> topics;
  std::uint64_t at = index_pos;
  for (std::uint32_t i = 0; i < connection_count; ++i) {
    const Record r = read_record(
        file, at,
        "connection " + std::to_string(i + 1) + " of " + std::to_string(connection_count));
    expect_op(file, r, kOpConnection);
    const std::uint32_t id = field_u32(file, r, "conn");
    const std::string topic = field(file, r, "topic", 0);
    // The data is the connection's own header: a length and fields.
    const std::string data =
        file.read(r.data_pos, r.data_len, "the connection header of the " + r.what);
    Fields connection_fields;
    const std::string why = parse_fields(data.data(), data.size(), connection_fields);
    if (!why.empty()) file.fail("the connection header of the " + r.what + ": " + why);
    topics.emplace(id, topic);  // rosbag keeps the first of a repeated id
    at = r.data_pos + r.data_len;
  }

  struct ChunkInfo {
    std::uint64_t chunk_pos = 0;
    std::size_t connections = 0;  // distinct connection ids: index records after the chunk
    std::string what;
  };
  std::vector<ChunkInfo> infos;
  for (std::uint32_t i = 0; i < chunk_count; ++i) {
    const Record r = read_record(
        file, at, "chunk info " + std::to_string(i + 1) + " of " + std::to_string(chunk_count));
    expect_op(file, r, kOpChunkInfo);
    if (field_u32(file, r, "ver") != 1) file.fail("the " + r.what + " is not version 1");
    ChunkInfo info;
    info.chunk_pos = field_u64(file, r, "chunk_pos");
    field(file, r, "start_time", 8);
    field(file, r, "end_time", 8);
    const std::uint32_t count = field_u32(file, r, "count");
    if (r.data_len != std::uint64_t{8} * count) {
      file.fail("the " + r.what + " lists " + std::to_string(count) + " connections in " +
                std::to_string(r.data_len) + " bytes (8 each)");
    }
    const std::string data = file.read(r.data_pos, r.data_len, "the data of the " + r.what);
    std::set<std::uint32_t> ids;
    for (std::uint32_t k = 0; k < count; ++k) ids.insert(u32_at(data.data() + 8 * k));
    info.connections = ids.size();
    info.what = r.what;
    infos.push_back(info);
    at = r.data_pos + r.data_len;
  }

  BagStructure out;
  for (const ChunkInfo& info : infos) {
    const Chunk chunk = read_chunk_header(file, info.chunk_pos, info.what);
    std::string bytes;
    bool decoded = false;
    std::string chunk_problem;
    std::uint64_t index_at = chunk.data_pos + chunk.data_len;
    for (std::size_t k = 0; k < info.connections; ++k) {
      const Record r = read_record(file, index_at, "index");
      expect_op(file, r, kOpIndexData);
      if (field_u32(file, r, "ver") != 1) file.fail("the " + r.what + " is not version 1");
      const std::uint32_t id = field_u32(file, r, "conn");
      const std::uint32_t count = field_u32(file, r, "count");
      const auto topic = topics.find(id);
      if (topic == topics.end()) {
        file.fail("the " + r.what + " names connection " + std::to_string(id) +
                  ", which the bag does not define");
      }
      if (r.data_len != std::uint64_t{12} * count) {
        file.fail("the " + r.what + " lists " + std::to_string(count) + " entries in " +
                  std::to_string(r.data_len) + " bytes (12 each)");
      }
      const std::string entries = file.read(r.data_pos, r.data_len, "the entries of the " + r.what);
      for (std::uint32_t e = 0; e < count; ++e) {
        const char* p = entries.data() + 12 * e;
        const std::uint64_t sec = u32_at(p), nsec = u32_at(p + 4);
        const std::uint32_t offset = u32_at(p + 8);
        if (sec + nsec / 1000000000u > std::numeric_limits<std::uint32_t>::max()) {
          file.fail("entry " + std::to_string(e + 1) + " of the " + r.what +
                    " has a time past ROS's range");
        }
        if (sec == 0 && nsec == 0) continue;  // rosbag drops entries at time 0
        if (!decoded) {
          chunk_problem = chunk_bytes(file, chunk, bytes);
          decoded = true;
        }
        std::string why = chunk_problem.empty() ? message_problem(bytes, offset) : chunk_problem;
        if (why.empty()) continue;
        const std::int64_t receipt_ns = static_cast<std::int64_t>(sec * 1000000000u + nsec);
        out.bad_messages.emplace(topic->second, receipt_ns);
        if (++out.bad_entry_count <= kBadEntriesNamed) {
          out.bad_entry_reasons.push_back("entry " + std::to_string(e + 1) + " of the " + r.what +
                                          " (" + topic->second + ", chunk at byte " +
                                          std::to_string(chunk.pos) + "): " + why);
        }
      }
      index_at = r.data_pos + r.data_len;
    }
  }
  return out;
}

}  // namespace bag
}  // namespace virtual_go
