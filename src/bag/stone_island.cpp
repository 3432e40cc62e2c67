#include "virtual_go/bag/stone_island.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>

#include "virtual_go/common/validation.h"

namespace virtual_go {
namespace bag {
namespace {

constexpr std::int64_t kOpen = std::numeric_limits<std::int64_t>::max();

struct Node {
  std::size_t stone, segment;
  std::int64_t start_ns, end_ns;
};

std::size_t find_root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// The ~stones sample of a track at a stamp (one with velocities), or nullptr.
const OdomSample* sample_at(const StoneTrack& track, std::int64_t stamp_ns) {
  auto it = std::lower_bound(track.samples.begin(), track.samples.end(), stamp_ns,
                             [](const OdomSample& s, std::int64_t t) { return s.stamp_ns < t; });
  for (; it != track.samples.end() && it->stamp_ns == stamp_ns; ++it) {
    if (it->has_twist) return &*it;
  }
  return nullptr;
}

}  // namespace

StoneIslandResult check_stone_islands(const std::vector<IslandStone>& stones,
                                      const std::vector<SegmentEvent>& events,
                                      const std::vector<StonesSnapshot>& snapshots) {
  // Every contact segment of every stone is a node; a segment lasts until the next one starts.
  std::vector<Node> nodes;
  std::map<std::string, std::size_t> by_name;
  for (std::size_t s = 0; s < stones.size(); ++s) {
    by_name[stones[s].name] = s;
    if (stones[s].physics == nullptr) continue;
    const auto& segs = stones[s].physics->segments;
    for (std::size_t k = 0; k < segs.size(); ++k) {
      if (segs[k].kind != SegmentKind::contact) continue;
      nodes.push_back(
          {s, k, segs[k].plan.start_ns, k + 1 < segs.size() ? segs[k + 1].plan.start_ns : kOpen});
    }
  }
  auto node_of = [&](const std::string& name, std::int64_t stamp_ns) -> std::size_t {
    const auto it = by_name.find(name);
    if (it == by_name.end()) return nodes.size();
    for (std::size_t n = 0; n < nodes.size(); ++n) {
      if (nodes[n].stone == it->second && nodes[n].start_ns <= stamp_ns &&
          stamp_ns < nodes[n].end_ns) {
        return n;
      }
    }
    return nodes.size();
  };
  std::vector<std::size_t> parent(nodes.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<std::int64_t> first_link(nodes.size(), kOpen);
  for (const SegmentEvent& e : events) {
    if (e.stone.empty() || e.other_stone.empty()) continue;
    const std::size_t a = node_of(e.stone, e.stamp_ns), b = node_of(e.other_stone, e.stamp_ns);
    if (a == nodes.size() || b == nodes.size()) continue;  // not both in contact then
    const std::size_t ra = find_root(parent, a), rb = find_root(parent, b);
    const std::int64_t link = std::min({first_link[ra], first_link[rb], e.stamp_ns});
    parent[rb] = ra;
    first_link[ra] = link;
  }

  StoneIslandResult result;
  std::map<std::size_t, std::size_t> island_of_root;
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    const std::size_t r = find_root(parent, n);
    if (first_link[r] == kOpen) continue;  // never linked
    auto [it, added] = island_of_root.emplace(r, result.islands.size());
    if (added) {
      result.islands.emplace_back();
      result.islands.back().start_ns = first_link[r];
    }
    StoneIsland& island = result.islands[it->second];
    island.segments.emplace_back(nodes[n].stone, nodes[n].segment);
    island.end_ns = std::max(island.end_ns, nodes[n].end_ns);
  }
  std::sort(result.islands.begin(), result.islands.end(),
            [](const StoneIsland& a, const StoneIsland& b) { return a.start_ns < b.start_ns; });

  for (StoneIsland& island : result.islands) {
    std::set<std::size_t> members;
    for (const auto& seg : island.segments) members.insert(seg.first);
    std::vector<MotionModel> models;
    for (std::size_t m : members) {
      island.members.push_back(stones[m].name);
      models.push_back(model_from_info(*stones[m].info));
    }
    std::sort(island.members.begin(), island.members.end());
    double lowest = INFINITY, scale = 0.0;
    for (const StonesSnapshot& snap : snapshots) {
      if (snap.stamp_ns < island.start_ns || snap.stamp_ns >= island.end_ns) continue;
      double energy = 0.0, snap_scale = 0.0;
      bool complete = true;
      std::size_t k = 0;
      for (auto m = members.begin(); m != members.end() && complete; ++m, ++k) {
        const OdomSample* o =
            stones[*m].track ? sample_at(*stones[*m].track, snap.stamp_ns) : nullptr;
        if (o == nullptr) {
          complete = false;
          break;
        }
        try {
          const RigidBody body(models[k], state_from_odom(models[k], *o));
          const Eigen::Vector3d& g = stones[*m].info->gravity_world;
          energy += body.total_energy(g);
          snap_scale += energy_scale(body, g);
        } catch (const InvalidArgument&) {
          energy = NAN;  // a non-finite state: counted by the per-stone check; no figure here
        }
      }
      if (!complete) continue;
      ++island.snapshots;
      scale = std::max(scale, snap_scale);
      double rise = 0.0;
      if (std::isnan(energy)) {
        rise = NAN;
      } else if (std::isfinite(lowest) && scale > 0.0) {
        rise = (energy - lowest) / scale;
      }
      if (!std::isnan(island.max_energy_rise) &&
          (std::isnan(rise) || rise > island.max_energy_rise)) {
        island.max_energy_rise = rise;
        island.worst_stamp_ns = snap.stamp_ns;
      }
      if (std::isfinite(energy)) lowest = std::min(lowest, energy);
    }
  }
  for (std::size_t i = 0; i < result.islands.size(); ++i) {
    const double r = result.islands[i].max_energy_rise,
                 w = result.islands[result.worst].max_energy_rise;
    if (!std::isnan(w) && (std::isnan(r) || r > w)) result.worst = i;
  }
  return result;
}

void exempt_island_samples(const StoneIslandResult& result, std::vector<IslandStone>& stones) {
  for (const StoneIsland& island : result.islands) {
    for (const auto& [s, k] : island.segments) {
      PhysicsResult& physics = *stones[s].physics;
      double rise = 0.0;
      for (const PhysicsSample& p : physics.samples) {
        if (p.segment == k && p.stamp_ns < island.start_ns) rise = std::fmax(rise, p.energy_rise);
      }
      physics.segments[k].max_energy_rise = rise;
    }
  }
}

}  // namespace bag
}  // namespace virtual_go
