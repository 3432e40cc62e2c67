// A stone's identity in a World (docs/physics.md, "World"): given when the stone is added and
// never given again in that world, not even after the stone is removed or the world reset, so a
// caller (the node's ~place/~remove services, a replay) can hold it while other stones come and
// go. Indices (0 .. stone_count()-1, in the order of the ids) shift when a stone is removed;
// ids do not.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace virtual_go {

struct StoneId {
  std::uint64_t value = 0;

  friend bool operator==(StoneId a, StoneId b) { return a.value == b.value; }
  friend bool operator!=(StoneId a, StoneId b) { return a.value != b.value; }
  friend bool operator<(StoneId a, StoneId b) { return a.value < b.value; }
};

// "stone 7": how errors and logs name a stone.
inline std::string stone_id_name(StoneId id) { return "stone " + std::to_string(id.value); }

}  // namespace virtual_go

template <>
struct std::hash<virtual_go::StoneId> {
  std::size_t operator()(virtual_go::StoneId id) const noexcept {
    return std::hash<std::uint64_t>()(id.value);
  }
};
