#include "virtual_go/bag/stone_overlap.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <utility>

#include "virtual_go/geometry/lens_geometry.h"
#include "virtual_go/geometry/lens_pair_distance.h"

namespace virtual_go {
namespace bag {

StoneOverlapResult check_stone_overlaps(const std::vector<StoneTrack>& tracks,
                                        const std::vector<StonesSnapshot>& snapshots) {
  StoneOverlapResult result;
  result.min_gap_m = std::numeric_limits<double>::infinity();
  // One lens per stone, from its ~stones width and height; none when they are unusable.
  std::vector<std::optional<LensGeometry>> lenses;
  for (const StoneTrack& t : tracks) {
    try {
      lenses.emplace_back(LensGeometry(LensShape(t.width_m, t.height_m)));
    } catch (const std::exception&) {
      lenses.emplace_back();
    }
  }
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> overlap_of_pair;
  struct Entry {
    std::size_t track;
    LensPose pose;
    double reach_m;  // half width: the lens lies inside this ball about its centre
  };
  std::vector<Entry> entries;
  struct Measured {
    bool valid = false;
    LensPose first, second;
    double gap_m = 0.0;
  };
  std::map<std::pair<std::size_t, std::size_t>, Measured> measured;
  auto same_pose = [](const LensPose& a, const LensPose& b) {
    return std::memcmp(a.center_world.data(), b.center_world.data(), 3 * sizeof(double)) == 0 &&
           std::memcmp(a.axis_world.data(), b.axis_world.data(), 3 * sizeof(double)) == 0;
  };
  for (const StonesSnapshot& snap : snapshots) {
    entries.clear();
    for (std::size_t i = 0; i < snap.track.size(); ++i) {
      const std::size_t k = snap.track[i];
      const double norm = snap.orientation_raw[i].norm();
      if (k >= lenses.size() || !lenses[k] || !snap.position_world[i].allFinite() ||
          !std::isfinite(norm) || norm == 0.0) {
        ++result.unusable;
        continue;
      }
      const Eigen::Quaterniond q = snap.orientation_raw[i].normalized();
      entries.push_back(
          {k, {snap.position_world[i], q * Eigen::Vector3d::UnitZ()}, lenses[k]->half_width()});
    }
    if (entries.size() < 2) continue;
    ++result.snapshots;
    // Sweep along x: only stones whose balls overlap in x can touch.
    std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
      return a.pose.center_world.x() < b.pose.center_world.x();
    });
    for (std::size_t i = 0; i < entries.size(); ++i) {
      for (std::size_t j = i + 1; j < entries.size(); ++j) {
        const Entry& a = entries[i];
        const Entry& b = entries[j];
        const double reach = a.reach_m + b.reach_m;
        if (b.pose.center_world.x() - a.pose.center_world.x() > reach) break;
        if ((b.pose.center_world - a.pose.center_world).norm() > reach) continue;
        const auto [first, second] = std::minmax(a.track, b.track);
        // Resting stones keep their poses bit for bit: a pair measured at the same poses before
        // has the same distance.
        const bool a_first = a.track == first;
        const LensPose& pose_first = a_first ? a.pose : b.pose;
        const LensPose& pose_second = a_first ? b.pose : a.pose;
        Measured& m = measured[{first, second}];
        if (!m.valid || !same_pose(m.first, pose_first) || !same_pose(m.second, pose_second)) {
          m = {true, pose_first, pose_second,
               lens_pair_distance(*lenses[first], pose_first, *lenses[second], pose_second).gap_m};
        }
        const double gap = m.gap_m;
        ++result.pairs_measured;
        if (gap < result.min_gap_m) {
          result.min_gap_m = gap;
          result.stone_a = tracks[first].name;
          result.stone_b = tracks[second].name;
          result.stamp_ns = snap.stamp_ns;
        }
        if (!(gap < 0.0)) continue;
        const auto [it, added] =
            overlap_of_pair.emplace(std::make_pair(first, second), result.overlaps.size());
        if (added) {
          result.overlaps.push_back(
              {tracks[first].name, tracks[second].name, snap.stamp_ns, 0.0, 0});
        }
        PairOverlap& o = result.overlaps[it->second];
        ++o.stamps;
        if (-gap > o.depth_m) {
          o.depth_m = -gap;
          o.stamp_ns = snap.stamp_ns;
        }
      }
    }
  }
  return result;
}

}  // namespace bag
}  // namespace virtual_go
