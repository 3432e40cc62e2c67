// rosbag I/O for bag_report: reads a bag into the plain Recording the analysis works on.
#pragma once

#include <stdexcept>
#include <string>

#include "virtual_go/bag/recording.h"

namespace virtual_go {
namespace bag {

// The bag cannot be read at all (missing, not a bag, no index); what() is one line.
class BagReadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Reads every message's stamp, and ~info, ~odom and ~events of the node in node_namespace
// (e.g. "/stone"). A topic not found under that name is looked up by its message type when
// exactly one topic has it. The file's records are checked first (bag_structure.h): damage to
// the file header, connections, chunk infos, chunks or index records throws BagReadError naming
// it; an index entry that points at no message is skipped and listed in Recording::problems,
// as is damage inside a message and anything missing.
Recording read_recording(const std::string& path, const std::string& node_namespace);

}  // namespace bag
}  // namespace virtual_go
