// NonsmoothIsland's contacts: their detection (gather, the pair distances and their memo, the
// obstacles) and step 2, the position corrections out of every overlap (project).
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "nonsmooth_island_impl.h"
#include "virtual_go/geometry/lens_pair_distance.h"
#include "virtual_go/geometry/rotation.h"
#include "virtual_go/world/nonsmooth_island.h"

namespace virtual_go {
namespace {

// A position correction moves this much (m) beyond the touching pose, so that the recomputed
// gap, whose round-off is ~1e-17 m, comes out non-negative.
constexpr double kCorrectionSlackM = 1e-15;
// No handed-out state overlaps by more than this (m): gaps are exact to ~1e-17 m.
constexpr double kGapToleranceM = 1e-12;
constexpr int kMaxCorrections = 16;        // per member and sweep, board and table
constexpr int kMaxProjectionSweeps = 100;  // then the touching members keep their poses
// The joint solve's passes, each re-linearised at the poses the last one left.
constexpr int kMaxJointPasses = 30;
// A pair correction along n does not move a stone whose board contact normal makes a cosine
// above this with the direction it would be pushed into the board.
constexpr double kBlockedCosine = 1e-6;
// A member leaves the island only with no other member within this many contact margins: the
// World joins stones in contact within one margin (touching, approaching or not), so a member let
// go just beyond one margin would rejoin within a few passes, again and again (a cradle row on
// the real board: 754 islands of ~2 sub-steps each, resting at 2.3 s instead of 0.14 s).
constexpr double kKeepMarginFactor = 10.0;

using nonsmooth_island_detail::apart_by_bounds;

bool same_pose(const LensPose& x, const LensPose& y) {
  return x.center_world == y.center_world && x.axis_world == y.axis_world;
}

// A stone pair at a sweep's poses that overlaps or touches: normal from a to b, its gap (m), and
// the shares of a separation along the normal each member takes (inverse masses; 0 for a member
// the board holds).
struct PairGap {
  std::size_t a, b;
  Eigen::Vector3d normal_world;
  double gap_m;
  double share_a, share_b;
};

// At most this many pairs are separated jointly (a dense solve); more go pair by pair.
constexpr std::size_t kMaxJoint = 24;
// A pair touching within this (m) joins a joint separation that would press it into overlap.
constexpr double kTouchingM = 2.0 * kGapToleranceM;

// How much row's gap grows per unit separation of pair `by` (its members moved by their shares
// along its normal), to first order: along row's normal.
double coupling(const PairGap& row, const PairGap& by) {
  const auto moved = [](const PairGap& o, std::size_t i) -> Eigen::Vector3d {
    if (i == o.b) return o.share_b * o.normal_world;
    if (i == o.a) return -o.share_a * o.normal_world;
    return Eigen::Vector3d::Zero();
  };
  return row.normal_world.dot(moved(by, row.b) - moved(by, row.a));
}

// The separations (m) along each pair's normal that make every gap of `active` the slack at
// once, to first order: sum_j coupling(k, j) s_j = slack - gap_k (unit diagonal). Empty unless
// every separation is positive and finite and the system solved.
std::optional<Eigen::VectorXd> joint_separations(const std::vector<PairGap>& active) {
  const Eigen::Index k = static_cast<Eigen::Index>(active.size());
  Eigen::MatrixXd m(k, k);
  Eigen::VectorXd depth(k);
  for (Eigen::Index r = 0; r < k; ++r) {
    depth[r] = kCorrectionSlackM - active[static_cast<std::size_t>(r)].gap_m;
    for (Eigen::Index c = 0; c < k; ++c) {
      m(r, c) = coupling(active[static_cast<std::size_t>(r)], active[static_cast<std::size_t>(c)]);
    }
  }
  const Eigen::VectorXd separation = m.partialPivLu().solve(depth);
  for (Eigen::Index j = 0; j < k; ++j) {
    if (!std::isfinite(separation[j]) || !(separation[j] > 0.0)) return std::nullopt;
  }
  if (!((m * separation - depth).norm() <= 1e-9 * depth.norm())) return std::nullopt;
  return separation;
}

// The contact to push along (lens_pair_distance.h): not a tilted normal of touching rims.
// `best()` gives lens_pair_distance's contact; it is asked for only when the centre line is not
// certain to be the answer (a row at rest: the centre line, without the distance's multistart).
template <typename Best>
LensPairContact push_contact(const CentreLineContact& along, const Best& best) {
  if (along.certain) return along.contact;
  return lens_pair_push_contact(along, best(), kGapToleranceM);
}
template <typename Best>
LensPairContact pair_contact(const LensGeometry& a, const LensPose& pa, const LensGeometry& b,
                             const LensPose& pb, const Best& best) {
  return push_contact(lens_pair_centre_line(a, pa, b, pb, kGapToleranceM), best);
}

}  // namespace

bool NonsmoothIsland::free_of_board(const std::vector<MemberContacts>& mc) const {
  for (std::size_t i = 0; i < mc.size(); ++i) {
    // An obstacle is an outside body, as the board is.
    if (lattice_.active[i] && (mc[i].board > 0 || mc[i].obstacles > 0)) return false;
  }
  return true;
}

NonsmoothIsland::Kept NonsmoothIsland::kept_totals(const std::vector<MemberContacts>& mc) const {
  if (free_of_board(mc)) return Kept::all;
  // A frictionless contact on a horizontal face pushes along the vertical only: no horizontal
  // force and no torque about the vertical.
  for (std::size_t i = 0; i < mc.size(); ++i) {
    if (!lattice_.active[i]) continue;
    if (mc[i].obstacles > 0) return Kept::none;
    for (int k = 0; k < mc[i].board; ++k) {
      const BoardContact& c = mc[i].contact[k];
      const ContactMaterial& material = c.on_table() ? table_plastic_ : board_plastic_;
      if (material.friction != 0.0 || !c.lens.normal_world.head<2>().isZero(0.0)) {
        return Kept::none;
      }
    }
  }
  return Kept::horizontal;
}

bool NonsmoothIsland::project_jointly(std::vector<RigidBodyState>& s,
                                      std::vector<MemberContacts>& mc, bool commit, int& sweeps) {
  const std::size_t n = s.size();
  using Row = nonsmooth_island_detail::SolveRow;
  std::vector<double> inverse_mass;
  std::vector<Eigen::Matrix3d> inverse_inertia;
  std::vector<Eigen::Vector3d> dx, dtheta;
  double first_depth_m = 0.0;
  for (int pass = 0; pass < kMaxJointPasses; ++pass) {
    std::vector<Row> rows;
    bool overlap = false;
    joint_inverses(s, inverse_mass, inverse_inertia);  // the poses move between passes
    dx.assign(n, Eigen::Vector3d::Zero());
    dtheta.assign(n, Eigen::Vector3d::Zero());
    const auto add = [&](int a, int b, const Eigen::Vector3d& normal, const Eigen::Vector3d& point,
                         double gap, double mu) {
      Row r = nonsmooth_island_detail::make_row(a, b, normal, point, mu, s, inverse_mass,
                                                inverse_inertia);
      r.target_n = kCorrectionSlackM - gap;
      rows.push_back(r);
      if (gap < 0.0) overlap = true;
    };
    // Board and table rows without the rolling and spinning couples: those are laws of the
    // velocities (step 3's solve applies them). The projection is onto the motions the contacts
    // allow, and a wider set of motions only lowers the projected pose further, so step 2 still
    // pays for step 3 (physics.md, "A joint solve with rotation"). With the couples here (saturated
    // at l lambda_n in wedges) 4,600 of the crowd's solves reached the iteration cap; without
    // 1,000.
    for (std::size_t i = 0; i < n; ++i) {
      if (!lattice_.active[i] || !members_[i].board_enabled) continue;
      const LensPose pose = lens_pose(s[i]);
      const BoardContact& box = board_box(i, pose);
      if (box.lens.gap_m <= options_.contact_margin_m) {
        add(-1, static_cast<int>(i), box.lens.normal_world, box.lens.point_world, box.lens.gap_m,
            board_plastic_.friction);
        rows.back().key = -1 - 2 * static_cast<long>(i);
      }
      if (members_[i].board.table_gap(pose) <= options_.contact_margin_m) {
        const BoardContact t = members_[i].board.table(pose);
        add(-1, static_cast<int>(i), t.lens.normal_world, t.lens.point_world, t.lens.gap_m,
            table_plastic_.friction);
        rows.back().key = -2 - 2 * static_cast<long>(i);
      }
    }
    for (std::size_t a = 0; a < n; ++a) {
      if (!lattice_.active[a]) continue;
      for (std::size_t b = a + 1; b < n; ++b) {
        if (!lattice_.active[b] || apart_by_bounds(members_[a].board, s[a], members_[b].board, s[b],
                                                   options_.contact_margin_m)) {
          continue;
        }
        const LensPose pa = lens_pose(s[a]), pb = lens_pose(s[b]);
        if (apart_along_last_normal(a, pa, b, pb, options_.contact_margin_m)) continue;
        const LensPairContact c = pair_contact(
            members_[a].board.lens(), pa, members_[b].board.lens(), pb,
            [&]() -> const LensPairContact& { return pair_distance(a, pa, b, pb, commit); });
        if (c.gap_m > options_.contact_margin_m) continue;
        add(static_cast<int>(a), static_cast<int>(b), c.normal_world,
            0.5 * (c.point_a_world + c.point_b_world), c.gap_m, stone_plastic_.friction);
        rows.back().key = 1 + static_cast<long>(a * n + b);
      }
    }
    // Free of the board and the table, the corrections below keep a free island's totals
    // exactly (they only translate, by inverse masses): the joint solve is for islands on the
    // board.
    if (pass == 0 && std::none_of(rows.begin(), rows.end(), [](const Row& r) { return r.a < 0; })) {
      return false;
    }
    if (!overlap) return true;
    ++sweeps;
    if (pass == 0) nonsmooth_island_detail::load_warm(rows, warm_positions_);
    // A later pass removes what the first one's linearisation left (rotations move the contact
    // points to second order): it converges to the same tolerance of the first pass's depth, not
    // of its own residual, which would have it start a full solve over for picometres (20 % of
    // the cluster's position sweeps, measured in benchmark/many; the same rests in every test).
    if (pass == 0) {
      for (const Row& r : rows) first_depth_m = std::max(first_depth_m, std::abs(r.target_n));
    }
    const int iterations = nonsmooth_island_detail::solve_rows(rows, dx, dtheta, first_depth_m);
    if (commit) count_joint_solve(iterations);
    if (pass == 0 && commit) nonsmooth_island_detail::store_warm(rows, warm_positions_);
    for (std::size_t i = 0; i < n; ++i) {
      if (!lattice_.active[i] || (dx[i].isZero(0.0) && dtheta[i].isZero(0.0))) continue;
      s[i].position_world += dx[i];
      s[i].orientation = (rotation_exp(dtheta[i]) * s[i].orientation).normalized();
      mc[i].loaded = true;
    }
    if (commit) ++counters_.projections;
  }
  return false;
}

void NonsmoothIsland::project(std::vector<RigidBodyState>& s, std::vector<MemberContacts>& mc,
                              bool commit, int& sweeps) {
  if (options_.joint_solve) {
    sweeps = 0;
    if (project_jointly(s, mc, commit, sweeps)) {
      project_obstacles(s, mc, commit);
      return;
    }
  }
  const std::size_t n = s.size();
  // The board normals each member lies on (within the margin after its board corrections).
  std::vector<int>& supports = projection_.supports;
  supports.assign(n, 0);
  std::vector<Eigen::Vector3d>& support_normal = projection_.support_normal;
  support_normal.resize(2 * n);
  // Corrections only translate, so each member's axis is the same through every sweep.
  std::vector<Eigen::Vector3d>& axis_world = projection_.axis_world;
  axis_world.resize(n);
  for (std::size_t i = 0; i < n; ++i) axis_world[i] = lens_pose(s[i]).axis_world;
  const auto pose_of = [&](std::size_t i) { return LensPose{s[i].position_world, axis_world[i]}; };
  // A member's board check and a pair's check are functions of the poses alone (a pair's distance
  // at the same poses is its memo's), so one that found no overlap is not repeated until a
  // correction moves a member it involves: the same results as a full sweep, with less work.
  std::vector<long>& moves = projection_.moves;
  std::vector<long>& board_clear_at = projection_.board_clear_at;
  std::vector<std::pair<long, long>>& pair_clear_at = projection_.pair_clear_at;
  moves.assign(n, 0);
  board_clear_at.assign(n, -1);
  pair_clear_at.assign(n * n, {-1, -1});
  std::vector<PairGap> active, touching;  // a sweep's overlapping and touching pairs
  for (sweeps = 0; sweeps < kMaxProjectionSweeps; ++sweeps) {
    bool corrected = false;
    // The board and the table: translate along the deeper contact's normal (their normals are
    // the separating directions, so one correction along one of them makes that gap zero).
    for (std::size_t i = 0; i < n; ++i) {
      if (!lattice_.active[i] || !members_[i].board_enabled || board_clear_at[i] == moves[i]) {
        continue;
      }
      for (int k = 0; k < kMaxCorrections; ++k) {
        const LensPose pose = pose_of(i);
        // Only gaps and normals are needed here: the table's normal is +z, so its witness point
        // (the dearer part) is never computed.
        const BoardContact& box = board_box(i, pose);
        const double table_gap_m = members_[i].board.table_gap(pose);
        const bool table_deeper = table_gap_m < box.lens.gap_m;
        const double deeper_gap_m = table_deeper ? table_gap_m : box.lens.gap_m;
        const Eigen::Vector3d deeper_normal =
            table_deeper ? Eigen::Vector3d::UnitZ() : box.lens.normal_world;
        if (k == 0) {
          supports[i] = 0;
          if (box.lens.gap_m <= options_.contact_margin_m) {
            support_normal[2 * i + supports[i]++] = box.lens.normal_world;
          }
          if (table_gap_m <= options_.contact_margin_m) {
            support_normal[2 * i + supports[i]++] = Eigen::Vector3d::UnitZ();
          }
        }
        if (deeper_gap_m >= 0.0) {
          board_clear_at[i] = moves[i];
          break;
        }
        if (commit) {
          counters_.deepest_overlap_m = std::max(counters_.deepest_overlap_m, -deeper_gap_m);
          ++counters_.projections;
        }
        s[i].position_world += (kCorrectionSlackM - deeper_gap_m) * deeper_normal;
        ++moves[i];
        mc[i].loaded = true;
        corrected = true;
      }
    }
    // Stone pairs: a pair's gap at the present poses when it overlaps or touches, with the
    // shares of a separation: both along the pair normal, split by inverse mass; a stone that the
    // correction would press into a board contact it lies on stays (the board holds it).
    const auto pair_gap = [&](std::size_t a, std::size_t b) -> std::optional<PairGap> {
      std::pair<long, long>& clear_at = pair_clear_at[a * n + b];
      if (clear_at == std::make_pair(moves[a], moves[b])) return std::nullopt;
      if (apart_by_bounds(members_[a].board, s[a], members_[b].board, s[b], 0.0)) {
        clear_at = {moves[a], moves[b]};
        return std::nullopt;
      }
      const LensPose pa = pose_of(a), pb = pose_of(b);
      if (apart_along_last_normal(a, pa, b, pb, 0.0)) {
        clear_at = {moves[a], moves[b]};
        return std::nullopt;
      }
      const LensPairContact c = pair_contact(
          members_[a].board.lens(), pa, members_[b].board.lens(), pb,
          [&]() -> const LensPairContact& { return pair_distance(a, pa, b, pb, commit); });
      if (c.gap_m >= 0.0) {
        clear_at = {moves[a], moves[b]};
        if (c.gap_m >= kTouchingM) return std::nullopt;
      }
      auto blocked = [&](std::size_t i, const Eigen::Vector3d& push) {
        for (int k = 0; k < supports[i]; ++k) {
          if (push.dot(support_normal[2 * i + k]) < -kBlockedCosine) return true;
        }
        return false;
      };
      double wa = 1.0 / members_[a].setup.model.mass_properties().mass();
      double wb = 1.0 / members_[b].setup.model.mass_properties().mass();
      const bool hold_a = blocked(a, -c.normal_world), hold_b = blocked(b, c.normal_world);
      if (hold_a != hold_b) {
        if (hold_a) wa = 0.0;
        if (hold_b) wb = 0.0;
      }
      return PairGap{a, b, c.normal_world, c.gap_m, wa / (wa + wb), wb / (wa + wb)};
    };
    const auto separate = [&](const PairGap& o, double separation_m) {
      s[o.a].position_world -= (o.share_a * separation_m) * o.normal_world;
      s[o.b].position_world += (o.share_b * separation_m) * o.normal_world;
      ++moves[o.a];
      ++moves[o.b];
      if (commit) {
        counters_.deepest_overlap_m = std::max(counters_.deepest_overlap_m, -o.gap_m);
        ++counters_.projections;
        ++counters_.pair_projections;
      }
      mc[o.a].loaded = mc[o.b].loaded = true;
      corrected = true;
    };
    // Separated jointly: the separations that make every overlapping pair's gap the slack at
    // once, where every touching pair they would press into overlap (to first order) joins
    // them, until none would (an active set). Pair by pair, a stone wedged between two leaning
    // neighbours converged by 0.3 to 0.5 per sweep, the correction out of one pressing it into
    // the other, which only touched (12.7 sweeps per sub-step in the cluster scene). When a
    // separation comes out non-positive or the system is singular: pair by pair, each with the
    // poses the corrections before it left.
    active.clear();
    touching.clear();
    for (std::size_t a = 0; a < n; ++a) {
      if (!lattice_.active[a]) continue;
      for (std::size_t b = a + 1; b < n; ++b) {
        if (!lattice_.active[b]) continue;
        if (const std::optional<PairGap> o = pair_gap(a, b)) {
          (o->gap_m < 0.0 ? active : touching).push_back(*o);
        }
      }
    }
    std::optional<Eigen::VectorXd> joint;
    const bool solve = !active.empty() && active.size() + touching.size() > 1 &&
                       active.size() + touching.size() <= kMaxJoint;
    for (bool grew = solve; grew;) {
      grew = false;
      joint = joint_separations(active);
      if (!joint) break;
      for (std::size_t t = 0; t < touching.size();) {
        double gap_after_m = touching[t].gap_m;
        for (std::size_t j = 0; j < active.size(); ++j) {
          gap_after_m += (*joint)[static_cast<Eigen::Index>(j)] * coupling(touching[t], active[j]);
        }
        if (gap_after_m < 0.0) {
          active.push_back(touching[t]);
          touching.erase(touching.begin() + static_cast<std::ptrdiff_t>(t));
          grew = true;
        } else {
          ++t;
        }
      }
    }
    if (joint) {
      for (std::size_t j = 0; j < active.size(); ++j) {
        separate(active[j], (*joint)[static_cast<Eigen::Index>(j)]);
      }
    } else {
      // A pair whose members no correction of this pass has moved is as it was found (a check is
      // a function of the poses): only the others are checked again.
      std::vector<char> moved(n, 0);
      for (const PairGap& found : active) {
        if (found.gap_m >= 0.0) continue;
        const std::optional<PairGap> o =
            moved[found.a] || moved[found.b] ? pair_gap(found.a, found.b) : found;
        if (o && o->gap_m < 0.0) {
          separate(*o, kCorrectionSlackM - o->gap_m);
          moved[o->a] = moved[o->b] = 1;
        }
      }
    }
    if (project_obstacles(s, mc, commit)) {
      corrected = true;
      for (long& m : moves) ++m;  // which members it moved is not tracked: check all again
    }
    if (!corrected) {
      ++sweeps;
      return;
    }
  }
}

bool NonsmoothIsland::project_obstacles(std::vector<RigidBodyState>& s,
                                        std::vector<MemberContacts>& mc, bool commit) {
  // Only the member moves, along the pair normal by the whole overlap, as out of the board.
  bool corrected = false;
  for (std::size_t a = 0; a < s.size(); ++a) {
    if (!lattice_.active[a]) continue;
    for (std::size_t o = 0; o < obstacles_.size(); ++o) {
      const std::optional<LensPairContact> found = obstacle_contact(a, s[a], o, 0.0, commit);
      if (!found) continue;
      const LensPairContact& c = *found;
      if (c.gap_m >= 0.0) continue;
      if (c.gap_m < -kGapToleranceM) obstacle_acted_[o] = 1;
      s[a].position_world -= (kCorrectionSlackM - c.gap_m) * c.normal_world;
      if (commit) {
        counters_.deepest_overlap_m = std::max(counters_.deepest_overlap_m, -c.gap_m);
        ++counters_.projections;
        ++counters_.obstacle_projections;
      }
      mc[a].loaded = true;
      corrected = true;
    }
  }
  return corrected;
}

void NonsmoothIsland::set_obstacles(std::vector<IslandObstacle> obstacles) {
  for (IslandObstacle& o : obstacles) o.state = o.state.validated();
  obstacles_ = std::move(obstacles);
  obstacle_memo_.assign(members_.size() * obstacles_.size(), PairMemo{});
}

std::optional<LensPairContact> NonsmoothIsland::obstacle_contact(std::size_t a,
                                                                 const RigidBodyState& s_a,
                                                                 std::size_t o, double margin_m,
                                                                 bool commit) {
  const double reach =
      members_[a].board.lens().half_width() + obstacles_[o].lens.half_width() + margin_m;
  if ((obstacles_[o].state.position_world - s_a.position_world).squaredNorm() > reach * reach)
    return std::nullopt;
  const LensPose pa = lens_pose(s_a);
  return pair_contact(
      members_[a].board.lens(), pa, obstacles_[o].lens, lens_pose(obstacles_[o].state),
      [&]() -> const LensPairContact& { return obstacle_distance(a, pa, o, commit); });
}

const LensPairContact& NonsmoothIsland::obstacle_distance(std::size_t a, const LensPose& pa,
                                                          std::size_t o, bool commit) {
  // The obstacle does not move: the memo holds while the member's pose is the same (bitwise).
  PairMemo& m = obstacle_memo_[a * obstacles_.size() + o];
  const auto same = [](const LensPose& x, const LensPose& y) {
    return x.center_world == y.center_world && x.axis_world == y.axis_world;
  };
  if (m.valid && same(m.pose_a, pa)) {
    if (commit) ++counters_.pair_distance_reuses;
    return m.contact;
  }
  m.contact = lens_pair_distance(members_[a].board.lens(), pa, obstacles_[o].lens,
                                 lens_pose(obstacles_[o].state));
  m.pose_a = pa;
  m.valid = true;
  if (commit) ++counters_.pair_distances;
  return m.contact;
}

const LensPairContact& NonsmoothIsland::pair_distance(std::size_t a, const LensPose& pa,
                                                      std::size_t b, const LensPose& pb,
                                                      bool commit) {
  // One memo per ordered pair: the projection's last sweep (no correction) and gather see the
  // same poses, and so often do the next sub-step's checks. Its contact is a function of the
  // poses and of the pair's previous normal (the warm start), so the committed sub-steps alone
  // write it: a partial sub-step (a sample between lattice points) reads it and keeps its own
  // contact aside, and the lattice's motion does not depend on the sample times.
  const std::size_t n = members_.size();
  if (pair_memo_.size() != n * n) pair_memo_.assign(n * n, PairMemo{});
  PairMemo& m = pair_memo_[a * n + b];
  if (m.valid && same_pose(m.pose_a, pa) && same_pose(m.pose_b, pb)) {
    if (commit) ++counters_.pair_distance_reuses;
    return m.contact;
  }
  // Seen before: warm-started from its last normal (lens_pair_distance.h).
  const LensPairContact contact =
      m.valid ? lens_pair_distance_from(members_[a].board.lens(), pa, members_[b].board.lens(), pb,
                                        m.contact.normal_world)
              : lens_pair_distance(members_[a].board.lens(), pa, members_[b].board.lens(), pb);
  if (!commit) {
    partial_contact_ = contact;
    return partial_contact_;
  }
  m.contact = contact;
  m.pose_a = pa;
  m.pose_b = pb;
  m.valid = true;
  if (commit) ++counters_.pair_distances;
  return m.contact;
}

const BoardContact& NonsmoothIsland::board_box(std::size_t i, const LensPose& pose) {
  if (box_memo_.size() != members_.size()) box_memo_.assign(members_.size(), BoxMemo{});
  BoxMemo& m = box_memo_[i];
  if (!m.valid || !same_pose(m.pose, pose)) {
    m.box = members_[i].board.box(pose);
    m.pose = pose;
    m.valid = true;
  }
  return m.box;
}

bool NonsmoothIsland::apart_along_last_normal(std::size_t a, const LensPose& pa, std::size_t b,
                                              const LensPose& pb, double gap_m) const {
  // The supporting-plane gap along the pair's last normal bounds its distance from below; where
  // it is positive the distance's ascent from that normal reaches the distance, and the push
  // contact's gap is at most a tolerance below it (lens_pair_distance.h). So above gap_m and
  // twice the tolerance, the pair's push contact is farther than gap_m: a check of one gap
  // instead of the distance (the projection's sweeps re-check pairs that one correction moved).
  return gap_along_last_normal(a, pa, b, pb) > gap_m + 2.0 * kGapToleranceM;
}

double NonsmoothIsland::carried_distance_bound(std::size_t a, const LensPose& pa, std::size_t b,
                                               const LensPose& pb) const {
  const std::size_t n = members_.size();
  if (pair_memo_.size() != n * n || !pair_memo_[a * n + b].valid) {
    return std::numeric_limits<double>::infinity();
  }
  const PairMemo& m = pair_memo_[a * n + b];
  return (lens_point_carried(m.contact.point_b_world, m.pose_b, pb) -
          lens_point_carried(m.contact.point_a_world, m.pose_a, pa))
      .norm();
}

double NonsmoothIsland::gap_along_last_normal(std::size_t a, const LensPose& pa, std::size_t b,
                                              const LensPose& pb) const {
  const std::size_t n = members_.size();
  if (pair_memo_.size() != n * n || !pair_memo_[a * n + b].valid) {
    return -std::numeric_limits<double>::infinity();
  }
  return lens_pair_gap_along(members_[a].board.lens(), pa, members_[b].board.lens(), pb,
                             pair_memo_[a * n + b].contact.normal_world);
}

bool NonsmoothIsland::gather(const std::vector<RigidBodyState>& s, std::vector<MemberContacts>& mc,
                             std::vector<PairContact>& pairs, bool commit) {
  const std::size_t n = s.size();
  bool clear = true;
  pairs.clear();
  std::vector<LensPose>& poses = gather_poses_;  // each member's once, not once per pair
  poses.assign(n, LensPose{});
  for (std::size_t i = 0; i < n; ++i) {
    if (lattice_.active[i]) poses[i] = lens_pose(s[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    mc[i].board = mc[i].stones = mc[i].near = 0;
    if (!lattice_.active[i] || !members_[i].board_enabled) continue;
    const LensPose& pose = poses[i];
    const BoardDistance& board = members_[i].board;
    const auto take = [&](const BoardContact& c) {
      if (c.lens.gap_m < -kGapToleranceM) clear = false;
      if (c.lens.gap_m <= options_.contact_margin_m) mc[i].contact[mc[i].board++] = c;
    };
    take(board_box(i, pose));
    // The table's witness point only when it is a contact (never while above the board).
    if (board.table_gap(pose) <= options_.contact_margin_m) take(board.table(pose));
  }
  for (std::size_t a = 0; a < n; ++a) {
    if (!lattice_.active[a]) continue;
    for (std::size_t b = a + 1; b < n; ++b) {
      const double keep_m =
          std::max(lattice_.keep_margin_m, kKeepMarginFactor * options_.contact_margin_m);
      if (!lattice_.active[b] ||
          apart_by_bounds(members_[a].board, s[a], members_[b].board, s[b], keep_m)) {
        continue;
      }
      const LensPose &pa = poses[a], &pb = poses[b];
      const double last_m = gap_along_last_normal(a, pa, b, pb);
      if (last_m > keep_m + 2.0 * kGapToleranceM) continue;  // apart_along_last_normal
      // Near but no contact, without the distance: the push contact's gap is at least the last
      // normal's less the tolerance (lens_pair_distance.h), above the margin, and at most the
      // distance, which is at most the last witness points' distance carried to these poses or
      // the centre line's upper bound.
      const bool no_contact = last_m > options_.contact_margin_m + 2.0 * kGapToleranceM;
      bool near_only = no_contact && carried_distance_bound(a, pa, b, pb) <= keep_m;
      CentreLineContact along;
      if (!near_only) {
        along = lens_pair_centre_line(members_[a].board.lens(), pa, members_[b].board.lens(), pb,
                                      kGapToleranceM);
        near_only = no_contact && along.upper_bound_m <= keep_m;
      }
      if (near_only) {
        ++mc[a].near;
        ++mc[b].near;
        continue;
      }
      const LensPairContact c = push_contact(
          along, [&]() -> const LensPairContact& { return pair_distance(a, pa, b, pb, commit); });
      if (c.gap_m < -kGapToleranceM) clear = false;
      if (c.gap_m > keep_m) continue;
      ++mc[a].near;
      ++mc[b].near;
      if (c.gap_m > options_.contact_margin_m) continue;
      ++mc[a].stones;
      ++mc[b].stones;
      pairs.push_back(PairContact{a, b, 0.5 * (c.point_a_world + c.point_b_world), c.normal_world});
    }
  }
  for (std::size_t a = 0; a < n; ++a) {
    mc[a].obstacles = 0;
    if (!lattice_.active[a]) continue;
    for (std::size_t o = 0; o < obstacles_.size(); ++o) {
      const std::optional<LensPairContact> found =
          obstacle_contact(a, s[a], o, options_.contact_margin_m, commit);
      if (!found) continue;
      const LensPairContact& c = *found;
      if (c.gap_m < -kGapToleranceM) clear = false;
      if (c.gap_m > options_.contact_margin_m) continue;
      ++mc[a].obstacles;
      pairs.push_back(
          PairContact{a, o, 0.5 * (c.point_a_world + c.point_b_world), c.normal_world, true});
    }
  }
  return clear;
}

}  // namespace virtual_go
