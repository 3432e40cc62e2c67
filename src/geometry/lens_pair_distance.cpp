#include "virtual_go/geometry/lens_pair_distance.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace virtual_go {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Newton on the sphere stops when its step turns n by less than this (rad). F alone resolves n
// only to ~sqrt(2 ulp(F) / curvature) ~ 5e-8 rad; the gradient (the witness points' tangential
// offset) resolves it to round-off, so small Newton steps are taken on the gradient's word.
constexpr double kStepRad = 1e-14;
// Below this step length (rad) a Newton step (positive definite model) is taken without
// comparing F, whose changes are then at its round-off.
constexpr double kTrustedStepRad = 1e-6;
constexpr int kMaxSteps = 60;
// Extra starts when no candidate is positive (overlapping or touching): a Fibonacci sphere.
constexpr int kSphereStarts = 96;
// Of the sphere's starts, how many of the best local maxima (at least this far apart, rad) are
// polished.
constexpr int kPolishedStarts = 4;
constexpr double kDistinctRad = 0.3;

// Added to the upper bound of F used to skip starts (m): far above the round-off of F (~1e-17 m
// for stones), far below the gaps between starts' values.
constexpr double kBoundSlackM = 1e-12;

// The closed-form candidates of lens_pair_distance: the centre line, 4 cap-cap, 2 + 2 cap-rim.
constexpr int kCandidates = 9;

struct Start {
  double value = -kInfinity;  // F(n), the supporting-plane gap along n
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
};

// The Fibonacci sphere of kSphereStarts unit directions, computed once.
const std::array<Eigen::Vector3d, kSphereStarts>& fibonacci_sphere() {
  static const std::array<Eigen::Vector3d, kSphereStarts> sphere = [] {
    std::array<Eigen::Vector3d, kSphereStarts> s;
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (int k = 0; k < kSphereStarts; ++k) {
      const double z = 1.0 - (2.0 * k + 1.0) / kSphereStarts;
      const double r = std::sqrt(1.0 - z * z);
      s[k] = Eigen::Vector3d(r * std::cos(golden * k), r * std::sin(golden * k), z);
    }
    return s;
  }();
  return sphere;
}

// The sphere's indices from its equator towards its poles: stones on the board lie side by side,
// so their best directions are near the horizontal, and visiting those first fills the prefix of
// choose_starts with large values early (fewer insertions, more starts skipped by their bound).
const std::array<int, kSphereStarts>& equator_first() {
  static const std::array<int, kSphereStarts> order = [] {
    std::array<int, kSphereStarts> o;
    for (int k = 0; k < kSphereStarts; ++k) o[k] = k;
    const auto height = [](int k) { return std::abs(2.0 * k + 1.0 - kSphereStarts); };
    std::stable_sort(o.begin(), o.end(), [&](int p, int q) { return height(p) < height(q); });
    return o;
  }();
  return order;
}

Eigen::Vector3d any_perpendicular(const Eigen::Vector3d& e) {
  const Eigen::Vector3d a =
      std::abs(e.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (a - a.dot(e) * e).normalized();
}

// The Hessian of a centred lens's support function at the unit direction n (1/m times m):
// R (1 - n n^T) where the support lies on a cap, a / |n_perp| (P_b - e e^T) on the rim.
Eigen::Matrix3d support_hessian(const LensGeometry& lens, const Eigen::Vector3d& b,
                                const Eigen::Vector3d& n) {
  const double ct = b.dot(n);
  if (lens.part_towards_plane(ct) != LensPart::rim) {
    return lens.sphere_radius() * (Eigen::Matrix3d::Identity() - n * n.transpose());
  }
  const Eigen::Vector3d perp = n - ct * b;
  const double s = perp.norm();
  const Eigen::Vector3d e = perp / s;
  return (lens.half_width() / s) *
         (Eigen::Matrix3d::Identity() - b * b.transpose() - e * e.transpose());
}

// The nearest point of the rim of the lens at `pose` to the point p (any rim point when p is
// on the axis).
Eigen::Vector3d nearest_rim_point(const LensGeometry& lens, const LensPose& pose,
                                  const Eigen::Vector3d& p) {
  const Eigen::Vector3d& b = pose.axis_world;
  Eigen::Vector3d radial = (p - pose.center_world) - (p - pose.center_world).dot(b) * b;
  const double length = radial.norm();
  radial = length > 0.0 ? Eigen::Vector3d(radial / length) : any_perpendicular(b);
  return pose.center_world + lens.half_width() * radial;
}

// A start's place in the order of falling F: its value and its index among the starts. Sorting
// these with the comparator on the value alone makes the same comparisons and the same moves
// as sorting the starts themselves, so it yields the same permutation, ties included.
struct Rank {
  double value;
  int index;
};

// The order's prefix that the choice of starts examines: 5 to 15 of the 105 starts for the
// overlapping pairs of the many-stone benchmark's cluster.
constexpr int kPrefix = 17;

// Chooses the starts to polish: walking the starts in the order of falling F that std::sort
// gives, each start at least kDistinctRad from every one chosen before, until kPolishedStarts
// are chosen. Touching flat stones give many starts of equal F, and std::sort's order among
// them decides which is polished first, so that order is the rule. Only the kPrefix largest
// values are kept in order (insertion into a short sorted list, O(starts)); where the walk stays
// in that prefix and the values it examined and the next one are strictly falling, every correct
// sort has the same prefix, std::sort's included. Otherwise (a tie, a NaN, a longer walk) the
// whole order is std::sort's, as before. `value(k)` is start k's F, `bound(k)` an upper bound of
// it: a start whose bound is below the prefix's last value when the prefix is full cannot enter
// it, and its F is computed only if the whole order is needed. `direction(k)` is its unit
// direction. The starts are visited in the order visit(0), visit(1), ... (a permutation), which
// changes how soon the prefix fills with large values, not the prefix. Every F that is computed is
// computed as before, so the result is the same, bit for bit.
template <typename Visit, typename Value, typename Bound, typename Direction>
int choose_starts(int total, const Visit& visit, const Value& value, const Bound& bound,
                  const Direction& direction,
                  std::array<Eigen::Vector3d, kPolishedStarts>* chosen) {
  const double distinct_cos = std::cos(kDistinctRad);
  const auto walk = [&](const Rank* order, int length, int* examined) {
    int chosen_count = 0;
    int k = 0;
    for (; k < length && chosen_count < kPolishedStarts; ++k) {
      const Eigen::Vector3d& n = direction(order[k].index);
      bool distinct = true;
      for (int c = 0; c < chosen_count; ++c) {
        distinct = distinct && (*chosen)[c].dot(n) < distinct_cos;
      }
      if (distinct) (*chosen)[chosen_count++] = n;
    }
    *examined = k;
    return chosen_count;
  };
  std::array<double, kCandidates + kSphereStarts> values;
  std::array<bool, kCandidates + kSphereStarts> known{};
  std::array<Rank, kPrefix> prefix;
  int size = 0;
  bool finite = true;
  for (int i = 0; i < total; ++i) {
    const int k = visit(i);
    if (size == kPrefix && bound(k) < prefix[kPrefix - 1].value) continue;
    const double v = value(k);
    values[k] = v;
    known[k] = true;
    finite = finite && !std::isnan(v);
    if (size == kPrefix && !(v > prefix[kPrefix - 1].value)) continue;
    int j = size < kPrefix ? size++ : kPrefix - 1;
    for (; j > 0 && prefix[j - 1].value < v; --j) prefix[j] = prefix[j - 1];
    prefix[j] = Rank{v, k};
  }
  int examined = 0;
  if (finite && size == kPrefix) {
    const int chosen_count = walk(prefix.data(), kPrefix, &examined);
    bool strict = examined < kPrefix;
    for (int k = 0; strict && k < examined; ++k) strict = prefix[k].value > prefix[k + 1].value;
    if (strict) return chosen_count;
  }
  std::array<Rank, kCandidates + kSphereStarts> order;
  for (int k = 0; k < total; ++k) order[k] = Rank{known[k] ? values[k] : value(k), k};
  std::sort(order.begin(), order.begin() + total,
            [](const Rank& p, const Rank& q) { return p.value > q.value; });
  return walk(order.data(), total, &examined);
}

class PairProblem {
 public:
  PairProblem(const LensGeometry& lens_a, const LensPose& pose_a, const LensGeometry& lens_b,
              const LensPose& pose_b)
      : lens_a_(lens_a), pose_a_(pose_a), lens_b_(lens_b), pose_b_(pose_b) {}

  double gap(const Eigen::Vector3d& n) const {
    return n.dot(pose_b_.center_world - pose_a_.center_world) -
           lens_a_.reach(pose_a_.axis_world.dot(n)) - lens_b_.reach(pose_b_.axis_world.dot(n));
  }

  LensPairContact contact(const Eigen::Vector3d& n) const {
    LensPairContact c;
    c.normal_world = n;
    c.gap_m = gap(n);
    // lens_support_world(.., m) is the point deepest along -m.
    c.point_a_world = lens_support_world(lens_a_, pose_a_, -n, &c.part_a);
    c.point_b_world = lens_support_world(lens_b_, pose_b_, n, &c.part_b);
    return c;
  }

  // Monotone Newton ascent of F on the sphere from the unit n; returns the final n.
  Eigen::Vector3d ascend(Eigen::Vector3d n, double* value, int* steps) const {
    double f = gap(n);
    for (int it = 0; it < kMaxSteps; ++it) {
      const LensPairContact c = contact(n);
      const Eigen::Vector3d w = c.point_b_world - c.point_a_world;  // gradient of F
      const Eigen::Vector3d t1 = any_perpendicular(n), t2 = n.cross(t1);
      Eigen::Matrix<double, 3, 2> t;
      t << t1, t2;
      const Eigen::Vector2d g = t.transpose() * w;
      if (g.norm() == 0.0) break;
      const Eigen::Matrix3d h = support_hessian(lens_a_, pose_a_.axis_world, n) +
                                support_hessian(lens_b_, pose_b_.axis_world, n);
      // Newton on the sphere: (T^T (H_A + H_B) T + F 1) xi = T^T w; where that matrix is not
      // positive definite (overlapping, F < 0), a gradient step scaled by the curvature.
      const Eigen::Matrix2d m = t.transpose() * h * t + f * Eigen::Matrix2d::Identity();
      Eigen::Vector2d xi;
      const Eigen::LLT<Eigen::Matrix2d> llt(m);
      const bool newton = llt.info() == Eigen::Success && m.determinant() > 0.0;
      if (newton) {
        xi = llt.solve(g);
      } else {
        xi = g / (h.trace() + std::abs(f));
      }
      if (newton && xi.norm() <= kTrustedStepRad) {
        n = (n + t * xi).normalized();
        f = gap(n);
        ++*steps;
        if (xi.norm() <= kStepRad) break;
        continue;
      }
      // Backtrack until F does not fall (F is C1 and the step an ascent direction). The full
      // step's length decides convergence: a shortened step says nothing about it.
      const double full_step = xi.norm();
      bool accepted = false;
      for (int halving = 0; halving < 60; ++halving) {
        const Eigen::Vector3d trial = (n + t * xi).normalized();
        const double f_trial = gap(trial);
        if (f_trial >= f) {
          n = trial;
          f = f_trial;
          accepted = true;
          break;
        }
        xi *= 0.5;
      }
      if (!accepted) break;
      ++*steps;
      if (full_step <= kStepRad) break;
    }
    *value = f;
    return n;
  }

 private:
  const LensGeometry& lens_a_;
  const LensPose& pose_a_;
  const LensGeometry& lens_b_;
  const LensPose& pose_b_;
};

}  // namespace

double lens_pair_gap_along(const LensGeometry& lens_a, const LensPose& pose_a,
                           const LensGeometry& lens_b, const LensPose& pose_b,
                           const Eigen::Vector3d& n) {
  return PairProblem(lens_a, pose_a, lens_b, pose_b).gap(n);
}

LensPairContact lens_pair_contact_along(const LensGeometry& lens_a, const LensPose& pose_a,
                                        const LensGeometry& lens_b, const LensPose& pose_b,
                                        const Eigen::Vector3d& n) {
  return PairProblem(lens_a, pose_a, lens_b, pose_b).contact(n);
}

namespace {

// lens_pair_distance, and with `warm` lens_pair_distance_from.
LensPairContact pair_distance(const LensGeometry& lens_a, const LensPose& pose_a,
                              const LensGeometry& lens_b, const LensPose& pose_b,
                              const Eigen::Vector3d* warm) {
  const PairProblem problem(lens_a, pose_a, lens_b, pose_b);
  const Eigen::Vector3d& xa = pose_a.center_world;
  const Eigen::Vector3d& xb = pose_b.center_world;
  const Eigen::Vector3d& ba = pose_a.axis_world;
  const Eigen::Vector3d& bb = pose_b.axis_world;

  // Closed-form candidates, one per pair of features: they are exact when their features are
  // the closest ones, and good starts otherwise. Each with its F, in a fixed array (this is
  // called for every pair of every sub-step of an island: no allocation).
  std::array<Start, kCandidates> candidates;
  int count = 0;
  auto add = [&](const Eigen::Vector3d& v) {
    const double length = v.norm();
    if (length > 0.0 && std::isfinite(length)) {
      const Eigen::Vector3d n = v / length;
      candidates[count++] = Start{problem.gap(n), n};
    }
  };
  add(xb - xa);
  for (int sa : {1, -1}) {
    const Eigen::Vector3d sphere_a = xa + (sa * lens_a.sphere_offset()) * ba;
    for (int sb : {1, -1}) {  // cap-cap: the line through the two sphere centres
      add(xb + (sb * lens_b.sphere_offset()) * bb - sphere_a);
    }
    add(nearest_rim_point(lens_b, pose_b, sphere_a) - sphere_a);  // cap of A - rim of B
  }
  for (int sb : {1, -1}) {  // rim of A - cap of B
    const Eigen::Vector3d sphere_b = xb + (sb * lens_b.sphere_offset()) * bb;
    add(sphere_b - nearest_rim_point(lens_a, pose_a, sphere_b));
  }
  // The rim-rim pair has no closed form; its optimum is reached by the ascent from any
  // positive start (when apart the positive maximum is unique).
  double best_value = -kInfinity;
  Eigen::Vector3d best_n = Eigen::Vector3d::UnitZ();
  for (int k = 0; k < count; ++k) {
    if (candidates[k].value > best_value) {
      best_value = candidates[k].value;
      best_n = candidates[k].n;
    }
  }
  int steps = 0;
  double value = 0.0;
  bool found = false;
  if (best_value > 0.0) {
    best_n = problem.ascend(best_n, &value, &steps);
    found = true;
  } else if (warm != nullptr && warm->allFinite() && warm->norm() > 0.0) {
    // Overlapping or touching: the local maximum reached from the previous normal, when it is
    // at least as good as the closed-form candidates (else the multistart below).
    const Eigen::Vector3d n = problem.ascend(warm->normalized(), &value, &steps);
    if (value >= best_value) {
      best_n = n;
      found = true;
    }
  }
  if (!found) {
    // Overlapping or touching: several local maxima are possible. Polish the best candidate
    // and the best well-separated local maxima of a Fibonacci sphere of directions.
    const std::array<Eigen::Vector3d, kSphereStarts>& sphere = fibonacci_sphere();
    const auto direction = [&](int k) -> const Eigen::Vector3d& {
      return k < count ? candidates[k].n : sphere[k - count];
    };
    const auto start_value = [&](int k) {
      return k < count ? candidates[k].value : problem.gap(sphere[k - count]);
    };
    // Each lens contains the ball of its half height c about its centre, so its reach is at
    // least c and F(n) <= n . (x_B - x_A) - c_A - c_B; kBoundSlackM covers the round-off of both.
    const Eigen::Vector3d centres = xb - xa;
    const double least_reaches = lens_a.half_height() + lens_b.half_height();
    const auto start_bound = [&](int k) {
      return direction(k).dot(centres) - least_reaches + kBoundSlackM;
    };
    std::array<Eigen::Vector3d, kPolishedStarts> chosen;
    // The candidates first (usually the largest values), then the sphere from its equator.
    const std::array<int, kSphereStarts>& sphere_order = equator_first();
    const auto visit = [&](int i) { return i < count ? i : count + sphere_order[i - count]; };
    const int chosen_count =
        choose_starts(count + kSphereStarts, visit, start_value, start_bound, direction, &chosen);
    best_value = -kInfinity;
    for (int c = 0; c < chosen_count; ++c) {
      const Eigen::Vector3d n = problem.ascend(chosen[c], &value, &steps);
      if (value > best_value) {
        best_value = value;
        best_n = n;
      }
    }
  }
  LensPairContact result = problem.contact(best_n);
  result.newton_steps = steps;
  return result;
}

}  // namespace

LensPairContact lens_pair_distance(const LensGeometry& lens_a, const LensPose& pose_a,
                                   const LensGeometry& lens_b, const LensPose& pose_b) {
  return pair_distance(lens_a, pose_a, lens_b, pose_b, nullptr);
}

LensPairContact lens_pair_distance_from(const LensGeometry& lens_a, const LensPose& pose_a,
                                        const LensGeometry& lens_b, const LensPose& pose_b,
                                        const Eigen::Vector3d& previous_normal_world) {
  return pair_distance(lens_a, pose_a, lens_b, pose_b, &previous_normal_world);
}

namespace {

// The point p lies inside the lens at `pose` by at least margin_m: inside both cap spheres.
bool inside_lens(const LensGeometry& lens, const LensPose& pose, const Eigen::Vector3d& p,
                 double margin_m) {
  const Eigen::Vector3d offset = lens.sphere_offset() * pose.axis_world;
  const double radius = lens.sphere_radius() - margin_m;
  return (p - (pose.center_world + offset)).norm() <= radius &&
         (p - (pose.center_world - offset)).norm() <= radius;
}

}  // namespace

CentreLineContact lens_pair_centre_line(const LensGeometry& lens_a, const LensPose& pose_a,
                                        const LensGeometry& lens_b, const LensPose& pose_b,
                                        double gap_tolerance_m) {
  // The midpoint must lie this far inside each lens (m): far above the round-off of the test
  // (~1e-17 m), far below the tolerance.
  constexpr double kInsideMarginM = 1e-15;
  CentreLineContact along;
  const Eigen::Vector3d centre_line = pose_b.center_world - pose_a.center_world;
  if (!(centre_line.norm() > 0.0)) return along;
  along.valid = true;
  along.contact = lens_pair_contact_along(lens_a, pose_a, lens_b, pose_b, centre_line.normalized());
  const LensPairContact& c = along.contact;
  const Eigen::Vector3d midpoint = 0.5 * (c.point_a_world + c.point_b_world);
  const bool overlapping = inside_lens(lens_a, pose_a, midpoint, kInsideMarginM) &&
                           inside_lens(lens_b, pose_b, midpoint, kInsideMarginM);
  along.upper_bound_m = overlapping ? 0.0 : (c.point_b_world - c.point_a_world).norm();
  along.certain = c.gap_m >= along.upper_bound_m - 0.5 * gap_tolerance_m;
  return along;
}

LensPairContact lens_pair_push_contact(const CentreLineContact& along, const LensPairContact& best,
                                       double gap_tolerance_m) {
  // Overlapping, a correction along the centre line may cost this much more than the shortest.
  constexpr double kCentreLineCost = 1.5;
  if (!along.valid) return best;
  const double gap_m = along.contact.gap_m;
  const bool as_good = gap_m >= best.gap_m - gap_tolerance_m;
  const bool cheap = best.gap_m < 0.0 && gap_m >= kCentreLineCost * best.gap_m;
  return as_good || cheap ? along.contact : best;
}

LensPairContact lens_pair_push_contact(const LensGeometry& lens_a, const LensPose& pose_a,
                                       const LensGeometry& lens_b, const LensPose& pose_b,
                                       const LensPairContact& best, double gap_tolerance_m) {
  return lens_pair_push_contact(
      lens_pair_centre_line(lens_a, pose_a, lens_b, pose_b, gap_tolerance_m), best,
      gap_tolerance_m);
}

}  // namespace virtual_go
