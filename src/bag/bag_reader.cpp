#include "virtual_go/bag/bag_reader.h"

#include <console_bridge/console.h>
#include <nav_msgs/Odometry.h>
#include <ros/serialization.h>
#include <rosbag/bag.h>
#include <rosbag/exceptions.h>
#include <rosbag/view.h>
#include <sys/stat.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_msgs/TFMessage.h>
#include <virtual_go/StoneEvent.h>
#include <virtual_go/StoneInfo.h>
#include <virtual_go/StoneStates.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "virtual_go/bag/bag_structure.h"
#include "virtual_go/bag/message_check.h"
#include "virtual_go/common/formatting.h"
#include "virtual_go/common/sim_time.h"

namespace virtual_go {
namespace bag {
namespace {

constexpr char kInfoType[] = "virtual_go/StoneInfo";
constexpr char kEventType[] = "virtual_go/StoneEvent";
constexpr char kOdomType[] = "nav_msgs/Odometry";
constexpr char kStonesType[] = "virtual_go/StoneStates";
constexpr char kTfType[] = "tf2_msgs/TFMessage";

std::int64_t to_ns(const ros::Time& t) { return static_cast<std::int64_t>(t.toNSec()); }

std::string normalise_namespace(std::string ns) {
  while (!ns.empty() && ns.back() == '/') ns.pop_back();
  if (ns.empty() || ns.front() != '/') ns.insert(ns.begin(), '/');
  return ns == "/" ? "" : ns;
}

// True when the message definition's first field is a std_msgs/Header, so the serialized
// message starts with seq (uint32), stamp.sec (uint32), stamp.nsec (uint32).
bool starts_with_header(const std::string& definition) {
  std::istringstream in(definition);
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line[start] == '#') continue;
    if (line.find('=') != std::string::npos) continue;  // a constant, not a field
    std::istringstream fields(line.substr(start));
    std::string type, name;
    fields >> type >> name;
    return (type == "Header" || type == "std_msgs/Header") && name == "header";
  }
  return false;
}

// Reads the header stamp of any message type from its serialized bytes (the types bag_report
// does not otherwise know still get header stamps, not receipt times).
bool header_stamp(const std::vector<std::uint8_t>& bytes, std::int64_t& stamp_ns) {
  if (bytes.size() < 12) return false;
  std::uint32_t sec = 0, nsec = 0;  // ROS serializes little-endian, as the hosts it runs on
  std::memcpy(&sec, bytes.data() + 4, 4);
  std::memcpy(&nsec, bytes.data() + 8, 4);
  stamp_ns = stamp_to_ns(sec, nsec);
  return true;
}

// The message of type M in `bytes`, or nothing when the bag's type differs (another md5sum,
// as rosbag's instantiate refuses it). Throws CorruptMessage for sizes the bytes cannot hold.
template <class M>
std::optional<M> decode(const rosbag::MessageInstance& m, const std::vector<std::uint8_t>& bytes) {
  if (m.getMD5Sum() != ros::message_traits::md5sum<M>()) return std::nullopt;
  return checked_deserialize<M>(bytes);
}

// The package's own types change between versions (issue 10 added the board to StoneInfo and
// the sub-ns offset to StoneEvent): a bag recorded with another version has the same type name
// and another md5sum, and cannot be read as this version's type.
template <class M>
bool other_version(const rosbag::MessageInstance& m) {
  return m.getDataType() == ros::message_traits::datatype<M>() &&
         m.getMD5Sum() != ros::message_traits::md5sum<M>();
}

// virtual_go/StoneEvent before it named its stone: the same fields without the two names at the
// end, so its bytes followed by two empty strings are a message of this version.
constexpr char kEventMd5BeforeNames[] = "297586e22de15a89da82e4c718f1324f";

std::optional<StoneEvent> decode_event_before_names(std::vector<std::uint8_t> bytes) {
  const std::size_t recorded = bytes.size();
  bytes.insert(bytes.end(), 8, 0);  // two string lengths of 0
  StoneEvent msg = checked_deserialize<StoneEvent>(bytes);
  // A message cut short would borrow the padding for its own fields.
  if (ros::serialization::serializationLength(msg) != recorded + 8) {
    throw CorruptMessage(
        "a ~events message of the version before stone names does not end where "
        "its fields do (" +
        std::to_string(recorded) + " bytes)");
  }
  return msg;
}

// Corrupt messages named in the problems; past this many, only counted.
constexpr std::size_t kCorruptNamed = 5;

class Reader {
 public:
  Reader(Recording& out, const std::string& node_namespace, const BagStructure& structure)
      : out_(out), ns_(normalise_namespace(node_namespace)), structure_(structure) {}

  void resolve_topics(const std::vector<const rosbag::ConnectionInfo*>& connections) {
    for (const rosbag::ConnectionInfo* c : connections) {
      types_[c->topic] = c->datatype;
      definitions_[c->topic] = c->msg_def;
      if (c->header) {
        const auto it = c->header->find("latching");
        if (it != c->header->end() && it->second == "1") latched_.insert(c->topic);
      }
    }
    info_topic_ = pick(ns_ + "/info", kInfoType, "~info");
    out_.odom_topic = pick(ns_ + "/odom", kOdomType, "~odom");
    out_.events_topic = pick(ns_ + "/events", kEventType, "~events");
    out_.stones_topic = pick(ns_ + "/stones", kStonesType, "~stones");
    pose_topic_ = ns_ + "/pose";
  }

  void read(const rosbag::MessageInstance& m) {
    // The index says where the message is; check_bag_structure found no message there, and
    // rosbag would read outside its chunk.
    if (structure_.bad_messages.count({m.getTopic(), to_ns(m.getTime())}) > 0) {
      ++bad_index_skipped_;
      return;
    }
    ++out_.message_count;
    const std::string& topic = m.getTopic();
    const std::string& type = m.getDataType();
    // The bytes once (the record's own length, within the chunk rosbag already holds); each
    // reader below checks the sizes they declare before it deserialises.
    bytes_.resize(m.size());
    ros::serialization::OStream stream(bytes_.data(), m.size());
    m.write(stream);
    try {
      if (type == kTfType && topic != "/tf_static") {
        read_tf(m);
      } else {
        TopicStamps& t = topic_stamps(topic, type);
        std::int64_t stamp = 0;
        if (t.header_stamps && header_stamp(bytes_, stamp)) {
          t.stamps_ns.push_back(stamp);
        } else {
          t.header_stamps = false;
          t.stamps_ns.push_back(to_ns(m.getTime()));
        }
      }
      if (topic == info_topic_) read_info(m);
      if (topic == out_.odom_topic) read_odom(m);
      if (topic == out_.events_topic) read_event(m);
      if (topic == out_.stones_topic) read_stones(m);
    } catch (const CorruptMessage& e) {
      // One bad message is skipped and named; the rest of the bag is read.
      if (++corrupt_ <= kCorruptNamed) {
        out_.problems.push_back("message " + std::to_string(out_.message_count) + " (" +
                                cut_user_text(topic) + " at " + receipt_text(m) + " s, " +
                                std::to_string(bytes_.size()) +
                                " bytes) is corrupt and was skipped: " + e.what());
      }
    }
  }

  void finish() {
    if (structure_.bad_entry_count > 0) {
      for (const std::string& why : structure_.bad_entry_reasons) {
        out_.problems.push_back("an index entry points at no message and was skipped: " + why);
      }
      out_.problems.push_back(std::to_string(structure_.bad_entry_count) +
                              " index entries point at no message (" +
                              std::to_string(bad_index_skipped_) + " messages skipped)");
    }
    if (corrupt_ > kCorruptNamed) {
      out_.problems.push_back(std::to_string(corrupt_) + " corrupt messages were skipped in all (" +
                              std::to_string(kCorruptNamed) + " named above)");
    }
    if (unknown_reasons_ > kCorruptNamed) {
      out_.problems.push_back(std::to_string(unknown_reasons_) +
                              " ~events messages with an unknown reason were skipped in all (" +
                              std::to_string(kCorruptNamed) + " named above)");
    }
    const std::string world = out_.info ? out_.info->world_frame : "world";
    const std::string stone = out_.info ? out_.info->stone_frame : "stone";
    for (TopicStamps& t : out_.topics) {
      if (t.topic == "/tf " + world + "->" + stone) t.at_node_rate = true;
    }
    attach_tf_poses(world);
    if (out_.message_count == 0) {
      out_.problems.push_back("the bag holds no messages");
      return;
    }
    if (!out_.info && other_version_.count(info_topic_) == 0) {
      out_.problems.push_back("no virtual_go/StoneInfo message (looked for " + ns_ +
                              "/info): physics check skipped");
    }
    if (out_.odom.empty() && out_.stone_tracks.empty()) {
      out_.problems.push_back("no nav_msgs/Odometry message (looked for " + ns_ +
                              "/odom): physics check skipped");
    }
  }

 private:
  // The topic named `name` if it has `type`, else the only topic of that type, else none.
  std::string pick(const std::string& name, const std::string& type, const std::string& what) {
    const auto it = types_.find(name);
    if (it != types_.end()) {
      if (it->second == type) return name;
      out_.problems.push_back(name + " has type " + it->second + ", expected " + type);
      return "";
    }
    std::vector<std::string> candidates;
    for (const auto& [topic, t] : types_) {
      if (t == type) candidates.push_back(topic);
    }
    if (candidates.size() == 1) return candidates.front();
    if (candidates.size() > 1) {
      std::string list;
      for (const std::string& c : candidates) list += " " + c;
      out_.problems.push_back("several " + type + " topics and none is " + name + ":" + list +
                              "; pass --node-namespace to choose " + what);
    }
    return "";
  }

  TopicStamps& topic_stamps(const std::string& topic, const std::string& type) {
    const auto it = index_.find(topic);
    if (it != index_.end()) return out_.topics[it->second];
    index_[topic] = out_.topics.size();
    TopicStamps t;
    t.topic = topic;
    t.datatype = type;
    const auto def = definitions_.find(topic);
    t.header_stamps = type == "geometry_msgs/TransformStamped" ||
                      (def != definitions_.end() && starts_with_header(def->second));
    t.aperiodic = latched_.count(topic) > 0 || type == kInfoType || type == kEventType ||
                  topic == "/tf_static";
    t.at_node_rate = topic == out_.odom_topic || topic == pose_topic_;
    out_.topics.push_back(t);
    return out_.topics.back();
  }

  void read_tf(const rosbag::MessageInstance& m) {
    const std::optional<tf2_msgs::TFMessage> tf = decode<tf2_msgs::TFMessage>(m, bytes_);
    if (!tf) return;
    // One row per frame pair: a /tf that carries several robots must not look jittery.
    for (const geometry_msgs::TransformStamped& t : tf->transforms) {
      TopicStamps& row =
          topic_stamps(m.getTopic() + " " + t.header.frame_id + "->" + t.child_frame_id,
                       "geometry_msgs/TransformStamped");
      row.stamps_ns.push_back(to_ns(t.header.stamp));
      // Poses of frames that may be stones (~stones names them): kept until finish().
      if (!out_.stones_topic.empty()) {
        OdomSample s;
        s.stamp_ns = to_ns(t.header.stamp);
        tf2::fromMsg(t.transform.translation, s.position_world);
        tf2::fromMsg(t.transform.rotation, s.orientation_raw);
        s.has_twist = false;
        tf_poses_[t.child_frame_id].push_back({t.header.frame_id, s});
      }
    }
  }

  // One ~stones message: a state per stone (its track) and the snapshot of all poses.
  void read_stones(const rosbag::MessageInstance& m) {
    const std::optional<StoneStates> msg = decode<StoneStates>(m, bytes_);
    if (!msg) return;
    const std::size_t n = msg->name.size();
    if (msg->color.size() != n || msg->width.size() != n || msg->height.size() != n ||
        msg->mass.size() != n || msg->pose.size() != n || msg->twist.size() != n) {
      throw CorruptMessage("a ~stones message's arrays differ in length (" + std::to_string(n) +
                           " names)");
    }
    StonesSnapshot snap;
    snap.stamp_ns = to_ns(msg->header.stamp);
    for (std::size_t i = 0; i < n; ++i) {
      const auto [it, added] = track_of_.emplace(msg->name[i], out_.stone_tracks.size());
      if (added) {
        StoneTrack t;
        t.name = msg->name[i];
        t.color = msg->color[i];
        t.width_m = msg->width[i];
        t.height_m = msg->height[i];
        t.mass_kg = msg->mass[i];
        out_.stone_tracks.push_back(t);
      }
      OdomSample s;
      s.stamp_ns = snap.stamp_ns;
      tf2::fromMsg(msg->pose[i].position, s.position_world);
      tf2::fromMsg(msg->pose[i].orientation, s.orientation_raw);
      // ~stones carries the world twist; the check reads it as ~odom's, in the stone frame.
      Eigen::Vector3d v_world, w_world;
      tf2::fromMsg(msg->twist[i].linear, v_world);
      tf2::fromMsg(msg->twist[i].angular, w_world);
      const Eigen::Quaterniond q_inverse = s.orientation_raw.normalized().conjugate();
      s.velocity_body = q_inverse * v_world;
      s.angular_velocity_body = q_inverse * w_world;
      out_.stone_tracks[it->second].samples.push_back(s);
      snap.track.push_back(it->second);
      snap.position_world.push_back(s.position_world);
      snap.orientation_raw.push_back(s.orientation_raw);
    }
    out_.snapshots.push_back(std::move(snap));
  }

  // The /tf poses (world -> a stone's name) join that stone's ~stones states, in stamp order; a
  // pose bitwise equal to one at the same stamp adds nothing and is dropped.
  void attach_tf_poses(const std::string& world) {
    for (TopicStamps& t : out_.topics) {
      for (const StoneTrack& track : out_.stone_tracks) {
        if (t.topic == "/tf " + world + "->" + track.name && !t.at_node_rate) t.on_change = true;
      }
    }
    auto same = [](const OdomSample& a, const OdomSample& b) {
      return a.stamp_ns == b.stamp_ns &&
             std::memcmp(a.position_world.data(), b.position_world.data(), 3 * sizeof(double)) ==
                 0 &&
             std::memcmp(a.orientation_raw.coeffs().data(), b.orientation_raw.coeffs().data(),
                         4 * sizeof(double)) == 0;
    };
    for (StoneTrack& track : out_.stone_tracks) {
      const auto found = tf_poses_.find(track.name);
      if (found == tf_poses_.end()) continue;
      std::vector<OdomSample>& samples = track.samples;
      for (const auto& [parent, sample] : found->second) {
        if (parent == world) samples.push_back(sample);
      }
      std::stable_sort(
          samples.begin(), samples.end(),
          [](const OdomSample& a, const OdomSample& b) { return a.stamp_ns < b.stamp_ns; });
      std::vector<OdomSample> kept;
      kept.reserve(samples.size());
      for (const OdomSample& s : samples) {
        bool duplicate = false;
        for (auto k = kept.rbegin(); k != kept.rend() && k->stamp_ns == s.stamp_ns; ++k) {
          if (same(*k, s) && (!s.has_twist || !k->has_twist)) {
            if (s.has_twist) *k = s;  // the state with the twist stays
            duplicate = true;
            break;
          }
        }
        if (!duplicate) kept.push_back(s);
      }
      samples = std::move(kept);
    }
    tf_poses_.clear();
  }

  // Once per topic: the bag holds `what` in another version of its message type M.
  template <class M>
  void note_other_version(const rosbag::MessageInstance& m, const std::string& what) {
    if (!other_version_.insert(m.getTopic()).second) return;
    out_.problems.push_back(what + " " + cut_user_text(m.getTopic()) + " is " + m.getDataType() +
                            " of another message version (md5sum " + m.getMD5Sum() +
                            ", this bag_report reads " + ros::message_traits::md5sum<M>() +
                            "): the bag was recorded by an older virtual_go (before the board "
                            "was added) and cannot be checked by this one; record it again");
  }

  void read_info(const rosbag::MessageInstance& m) {
    if (other_version<StoneInfo>(m)) return note_other_version<StoneInfo>(m, "~info");
    const std::optional<StoneInfo> msg = decode<StoneInfo>(m, bytes_);
    if (!msg || out_.info) return;  // the first info describes the run
    RecordingInfo info;
    info.topic = m.getTopic();
    info.stamp_ns = to_ns(msg->header.stamp);
    info.world_frame = msg->world_frame.empty() ? "world" : msg->world_frame;
    info.stone_frame = msg->stone_frame.empty() ? "stone" : msg->stone_frame;
    info.mass = msg->mass;
    tf2::fromMsg(msg->principal_moments, info.principal_moments_body);
    info.model = msg->model;
    info.integrator = msg->integrator;
    info.dt_s = msg->dt;
    info.dt_ns = msg->dt_ns;
    info.rate_hz = msg->rate;
    tf2::fromMsg(msg->gravity, info.gravity_world);
    info.width_m = msg->width;
    info.height_m = msg->height;
    info.board_enabled = msg->board_enabled;
    tf2::fromMsg(msg->board_size, info.board_size_m);
    info.board_rolling_resistance_m = msg->board_rolling_resistance;
    info.board_spinning_friction_m = msg->board_spinning_friction;
    info.table_rolling_resistance_m = msg->table_rolling_resistance;
    info.table_spinning_friction_m = msg->table_spinning_friction;
    out_.info = info;
  }

  void read_odom(const rosbag::MessageInstance& m) {
    const std::optional<nav_msgs::Odometry> msg = decode<nav_msgs::Odometry>(m, bytes_);
    if (!msg) return;
    OdomSample s;
    s.stamp_ns = to_ns(msg->header.stamp);
    tf2::fromMsg(msg->pose.pose.position, s.position_world);
    // tf2_eigen copies the components: | |q| - 1 | is measured on the quaternion as recorded.
    tf2::fromMsg(msg->pose.pose.orientation, s.orientation_raw);
    tf2::fromMsg(msg->twist.twist.linear, s.velocity_body);
    tf2::fromMsg(msg->twist.twist.angular, s.angular_velocity_body);
    out_.odom.push_back(s);
  }

  void read_event(const rosbag::MessageInstance& m) {
    std::optional<StoneEvent> msg;
    if (m.getDataType() == kEventType && m.getMD5Sum() == kEventMd5BeforeNames) {
      msg = decode_event_before_names(bytes_);
    } else if (other_version<StoneEvent>(m)) {
      return note_other_version<StoneEvent>(m, "~events");
    } else {
      msg = decode<StoneEvent>(m, bytes_);
    }
    if (!msg) return;
    SegmentEvent e;
    try {
      e.reason = parse_event_reason(msg->reason);
    } catch (const InvalidArgument& error) {
      // A reason this bag_report does not know has no rule to check its segment by.
      if (++unknown_reasons_ <= kCorruptNamed) {
        out_.problems.push_back("~events message " + std::to_string(out_.message_count) + " at " +
                                stamp_text(to_ns(msg->header.stamp)) +
                                " s was skipped: " + error.what());
      }
      return;
    }
    e.stamp_ns = to_ns(msg->header.stamp);
    e.time_offset_s = msg->time_offset;
    e.segment = msg->segment;
    e.detail = msg->detail;
    e.stone = msg->stone;
    e.other_stone = msg->other_stone;
    tf2::fromMsg(msg->pose.position, e.state.position_world);
    tf2::fromMsg(msg->pose.orientation, e.state.orientation);
    tf2::fromMsg(msg->twist.linear, e.state.velocity_world);
    tf2::fromMsg(msg->angular_momentum, e.state.angular_momentum_world);
    out_.events.push_back(e);
  }

  static std::string receipt_text(const rosbag::MessageInstance& m) {
    return stamp_text(to_ns(m.getTime()));
  }

  Recording& out_;
  std::string ns_;
  const BagStructure& structure_;
  std::size_t bad_index_skipped_ = 0;
  std::vector<std::uint8_t> bytes_;  // the current message, serialized
  std::size_t corrupt_ = 0;
  std::size_t unknown_reasons_ = 0;  // ~events messages skipped for their reason
  std::string info_topic_, pose_topic_;
  std::map<std::string, std::string> types_, definitions_;
  std::set<std::string> latched_;
  std::set<std::string> other_version_;  // topics already named as another message version
  std::map<std::string, std::size_t> index_;
  std::map<std::string, std::size_t> track_of_;  // stone name -> Recording::stone_tracks index
  // /tf poses by child frame, with their parent frame, until finish() knows the world frame.
  std::map<std::string, std::vector<std::pair<std::string, OdomSample>>> tf_poses_;
};

}  // namespace

Recording read_recording(const std::string& path, const std::string& node_namespace) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw BagReadError("no such file: " + path);
  if (!S_ISREG(st.st_mode)) throw BagReadError("not a regular file: " + path);

  // rosbag and cpp_common log damage through console_bridge on their way to throwing; the
  // exception is reported here in one line, so their multi-line messages are noise.
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_NONE);
  // rosbag trusts every length and offset in the file; they are checked first.
  const BagStructure structure = check_bag_structure(path);

  Recording out;
  out.path = path;
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagUnindexedException&) {
    throw BagReadError(path + " has no index (recording interrupted?); `rosbag reindex " + path +
                       "` may recover it");
  } catch (const rosbag::BagException& e) {
    throw BagReadError("cannot read " + path + " as a rosbag: " + e.what());
  } catch (const std::exception& e) {
    // A truncated index can hold garbage sizes (bad_alloc, length_error): same verdict.
    throw BagReadError("cannot read " + path + " as a rosbag (truncated or corrupt?): " + e.what());
  }

  Reader reader(out, node_namespace, structure);
  try {
    rosbag::View view(bag);
    reader.resolve_topics(view.getConnections());
    if (view.size() > 0) {
      out.bag_duration_s = (view.getEndTime() - view.getBeginTime()).toSec();
    }
    for (const rosbag::MessageInstance& m : view) reader.read(m);
  } catch (const std::exception& e) {
    // Damage inside a chunk: keep what was read and say where it stopped.
    out.problems.push_back("reading stopped after " + std::to_string(out.message_count) +
                           " messages (truncated or corrupt bag): " + e.what());
  }
  reader.finish();
  return out;
}

}  // namespace bag
}  // namespace virtual_go
