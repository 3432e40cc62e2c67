// Stones must not overlap: at every ~stones message (all stones' poses at one stamp) the signed
// distance of every pair of lenses that can touch, measured with the core's lens-lens distance
// (geometry/lens_pair_distance.h). A pair whose centres lie farther apart than the sum of the
// two half widths cannot touch (each lens lies inside the ball of radius half its width about
// its centre) and is not measured; a pair at the poses of its last measurement, bit for bit
// (stones at rest), keeps that distance.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "virtual_go/bag/recording.h"

namespace virtual_go {
namespace bag {

// A pair of stones that overlapped, at its deepest.
struct PairOverlap {
  std::string stone_a, stone_b;
  std::int64_t stamp_ns = 0;
  double depth_m = 0.0;    // penetration depth (> 0)
  std::size_t stamps = 0;  // ~stones messages in which the pair overlapped
};

struct StoneOverlapResult {
  std::size_t snapshots = 0;       // ~stones messages with two stones or more
  std::size_t pairs_measured = 0;  // pair distances computed (pairs within reach), all messages
  // The smallest gap of a measured pair (m; negative: minus the penetration depth), its pair
  // and stamp; +infinity when no pair came within reach.
  double min_gap_m = 0.0;
  std::string stone_a, stone_b;
  std::int64_t stamp_ns = 0;
  std::vector<PairOverlap> overlaps;  // every pair that overlapped (gap < 0), in first-seen order
  std::size_t unusable = 0;           // stone entries skipped: no lens, or a non-finite pose
};

StoneOverlapResult check_stone_overlaps(const std::vector<StoneTrack>& tracks,
                                        const std::vector<StonesSnapshot>& snapshots);

}  // namespace bag
}  // namespace virtual_go
