// The World's table of stones (docs/physics.md, "World"): per stone its identity, its body, and
// its data in two arrays as in Box2D v3's solver sets: the hot part every advance reads (state,
// mode, the times up to which a flight needs only sampling) and the record touched at events
// (the flight's anchor and cache, the contact model). Rows are kept in the order of their ids
// (ids only grow), so an id is found by binary search and an index is the rank of its id.
//
// The table also keeps the awake set: the stones not resting, in no particular order, and each
// stone's slot in it. Every mode change goes through set_mode (or sync_awake after a row was
// restored wholesale), so the set is always in step and advance_to visits only awake stones.
// Removing a row costs O(stones) (the rows after it shift down); it is a command, not a step.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/contact/plane_contact.h"
#include "virtual_go/world/flight_track.h"
#include "virtual_go/world/nonsmooth_contact.h"
#include "virtual_go/world/stone_id.h"
#include "virtual_go/world/stone_mode.h"

namespace virtual_go {

// Read on every call.
struct StoneHot {
  RigidBodyState state;
  double state_time_s = 0.0;
  StoneMode mode = StoneMode::flight;
  // Flight: sampling alone suffices for t < next_contact_s and t <= clear_until_s.
  double next_contact_s = std::numeric_limits<double>::infinity();
  double clear_until_s = std::numeric_limits<double>::infinity();
};

// Touched at events.
struct StoneRecord {
  FlightTrack flight;
  std::optional<PlaneContact> plane;
  std::optional<NonsmoothContact> nonsmooth;
  PlaneContactCounters plane_seen;  // the phase's counters already added to the world's
  NonsmoothCounters nonsmooth_seen;
  double transition_time_s = -std::numeric_limits<double>::infinity();
  int transitions_at_instant = 0;
  // A member of a stone-stone island (World's island list, by key): the island moves it, its
  // mode is nonsmooth_contact and `nonsmooth` is empty.
  std::optional<std::size_t> island;
  // Its island's rest was refused (NonsmoothContactOptions::hold_check): the islands it is a
  // member of use the joint solve until it leaves one.
  bool joint_solve = false;
};

class StoneTable {
 public:
  std::size_t size() const { return hot_.size(); }
  bool empty() const { return hot_.empty(); }

  StoneHot& hot(std::size_t i) { return hot_[i]; }
  const StoneHot& hot(std::size_t i) const { return hot_[i]; }
  StoneRecord& record(std::size_t i) { return records_[i]; }
  const StoneRecord& record(std::size_t i) const { return records_[i]; }
  StoneId id(std::size_t i) const { return ids_[i]; }
  std::size_t body(std::size_t i) const { return bodies_[i]; }
  // Every live stone's id, in index order (increasing).
  const std::vector<StoneId>& ids() const { return ids_; }
  // The index of a live stone; none for an id never given or removed. O(log stones).
  std::optional<std::size_t> index_of(StoneId id) const;

  // A new row at the end (the largest id so far), awake, in flight with default data, referring
  // to `body`. Returns its index.
  std::size_t add(std::size_t body);
  // Removes the row; the rows after it move down one index. Ids are never given again.
  void erase(std::size_t i);
  // Removes every row; ids go on from where they were.
  void clear();

  // The stones not resting (indices), in no particular order.
  const std::vector<std::size_t>& awake() const { return awake_; }
  bool all_resting() const { return awake_.empty(); }
  // Changes the mode through the table of transitions (world/stone_mode.h; std::logic_error for
  // a change not in it) and keeps the awake set in step.
  void set_mode(std::size_t i, StoneMode mode);
  // Brings the awake set in step with a mode restored wholesale (a snapshot).
  void sync_awake(std::size_t i);
  // The stones that came to rest since the last call (each once, perhaps awake again since):
  // the World enters them into its broad phase as resting. Cleared by clear() and erase().
  std::vector<std::size_t> take_fallen_asleep();

 private:
  static constexpr std::size_t kAsleep = std::numeric_limits<std::size_t>::max();
  std::vector<StoneHot> hot_;
  std::vector<StoneRecord> records_;
  std::vector<StoneId> ids_;
  std::vector<std::size_t> bodies_;
  std::vector<std::size_t> awake_;
  std::vector<std::size_t> awake_slot_;  // kAsleep while the stone rests
  std::vector<std::size_t> fallen_asleep_;
  StoneId next_id_;
};

}  // namespace virtual_go
