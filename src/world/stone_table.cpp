#include "virtual_go/world/stone_table.h"

#include <algorithm>

namespace virtual_go {

std::optional<std::size_t> StoneTable::index_of(StoneId id) const {
  const auto it = std::lower_bound(ids_.begin(), ids_.end(), id);
  if (it == ids_.end() || *it != id) return std::nullopt;
  return static_cast<std::size_t>(it - ids_.begin());
}

std::size_t StoneTable::add(std::size_t body) {
  const std::size_t i = hot_.size();
  hot_.emplace_back();
  records_.emplace_back();
  ids_.push_back(next_id_);
  ++next_id_.value;
  bodies_.push_back(body);
  awake_slot_.push_back(awake_.size());  // a new row is in flight: awake
  awake_.push_back(i);
  return i;
}

void StoneTable::erase(std::size_t i) {
  hot_[i].mode = StoneMode::resting;  // out of the awake set first (bookkeeping, not physics)
  sync_awake(i);
  hot_.erase(hot_.begin() + static_cast<std::ptrdiff_t>(i));
  records_.erase(records_.begin() + static_cast<std::ptrdiff_t>(i));
  ids_.erase(ids_.begin() + static_cast<std::ptrdiff_t>(i));
  bodies_.erase(bodies_.begin() + static_cast<std::ptrdiff_t>(i));
  awake_slot_.erase(awake_slot_.begin() + static_cast<std::ptrdiff_t>(i));
  for (std::size_t& a : awake_) {
    if (a > i) --a;
  }
  fallen_asleep_.clear();  // the World rebuilds its broad phase after a removal
}

void StoneTable::clear() {
  hot_.clear();
  records_.clear();
  ids_.clear();
  bodies_.clear();
  awake_.clear();
  awake_slot_.clear();
  fallen_asleep_.clear();
}

std::vector<std::size_t> StoneTable::take_fallen_asleep() {
  std::vector<std::size_t> taken;
  taken.swap(fallen_asleep_);
  return taken;
}

void StoneTable::set_mode(std::size_t i, StoneMode mode) {
  hot_[i].mode = transition(hot_[i].mode, mode);
  sync_awake(i);
}

void StoneTable::sync_awake(std::size_t i) {
  const bool awake = hot_[i].mode != StoneMode::resting;
  if (awake == (awake_slot_[i] != kAsleep)) return;
  if (awake) {
    awake_slot_[i] = awake_.size();
    awake_.push_back(i);
    return;
  }
  const std::size_t slot = awake_slot_[i], last = awake_.back();
  awake_[slot] = last;
  awake_slot_[last] = slot;
  awake_.pop_back();
  awake_slot_[i] = kAsleep;
  fallen_asleep_.push_back(i);
}

}  // namespace virtual_go
