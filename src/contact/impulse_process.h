// The impulse-space impact process shared by the one-body impact (impact.h) and the two-body
// impact (pair_impact.h): Coulomb friction integrated through the impact with the normal impulse
// as the independent variable, ended by Stronge's energetic coefficient (docs/physics.md,
// "Impact"). It sees only the contact's impulse response K (the sum over the bodies) and the
// approach velocity u-, in contact coordinates (t1, t2, n) scaled so that |u-| = 1, K_nn = 1.
// Never fails: the slip integration's work is bounded by ImpactOptions::max_steps, and a spent
// budget, a step below p's resolution or a jam hands the rest to a frictionless closed form that
// cannot add energy (Impact::frictionless_fallback).
#pragma once

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <boost/math/tools/roots.hpp>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <limits>

#include "virtual_go/contact/bracketed_root.h"
#include "virtual_go/contact/impact.h"

namespace virtual_go {
namespace impulse_process {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// In units of the approach speed |u-|: below kApproach a closing slip is taken straight onto 0
// (the direction has settled); below kSnapPerTolerance times the integration tolerance the
// integrated u_t is noise, so it counts as 0 and is set to exactly 0 (by a tangential impulse
// that removes energy, u_t^T K_tt^-1 u_t / 2).
constexpr double kApproach = 1e-8;
constexpr double kSnapPerTolerance = 100.0;
// Largest velocity error (units of |u-|) accepted when a nearly straight slip is taken as straight.
constexpr double kRay = 1e-13;

using SlipState = std::array<double, 3>;  // tangential impulse (2), normal work

inline Eigen::Vector3d any_perpendicular(const Eigen::Vector3d& e) {
  const Eigen::Vector3d a =
      std::abs(e.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (a - a.dot(e) * e).normalized();
}

inline Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& r) {
  Eigen::Matrix3d m;
  m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return m;
}

// The process's coordinates for the approach velocity u_world (m/s) at the unit normal n_world
// with the impulse response k_world (1/kg). Everything works on u / max|u_i|: a velocity of 1e-300
// m/s or a denormal one has a squared norm that underflows to 0, which would make the scaled
// process 0/0.
struct ContactFrame {
  bool approaching = false;    // u_n- < 0; when false nothing else is set
  Eigen::Matrix3d basis;       // columns t1 (along the initial slip, any tangent if none), t2, n
  Eigen::Matrix3d k;           // K in contact coordinates, 1/kg
  Eigen::Vector3d u;           // u- in contact coordinates, m/s
  Eigen::Matrix3d k_scaled;    // K / K_nn: the process's K
  Eigen::Vector3d u_scaled;    // u- / |u-|: the process's u-
  double impulse_scale = 0.0;  // N s per unit of the process's impulse, |u-| / K_nn
};

inline ContactFrame contact_frame(const Eigen::Vector3d& u_world, const Eigen::Vector3d& n_world,
                                  const Eigen::Matrix3d& k_world) {
  ContactFrame frame;
  const double u_max = u_world.cwiseAbs().maxCoeff();
  const Eigen::Vector3d u_unit = u_max > 0.0 ? Eigen::Vector3d(u_world / u_max) : u_world;
  frame.approaching = u_unit.dot(n_world) < 0.0;
  if (!frame.approaching) return frame;
  const Eigen::Vector3d u_t = u_unit - u_unit.dot(n_world) * n_world;
  const Eigen::Vector3d t1 = u_t.norm() > 1e-15 * u_unit.norm() ? Eigen::Vector3d(u_t.normalized())
                                                                : any_perpendicular(n_world);
  frame.basis << t1, n_world.cross(t1), n_world;
  frame.k = frame.basis.transpose() * k_world * frame.basis;
  frame.u = frame.basis.transpose() * u_world;
  const Eigen::Vector3d uc_unit = frame.basis.transpose() * u_unit;
  const double speed_unit = uc_unit.norm(), knn = frame.k(2, 2);
  frame.k_scaled = frame.k / knn;
  frame.u_scaled = uc_unit / speed_unit;
  frame.impulse_scale = u_max * speed_unit / knn;
  return frame;
}

// Smallest d >= 0 with un d + an d^2 / 2 = work (work >= 0): the end of restitution on a phase
// where du_n/dp = an is constant; +infinity if never.
inline double restitution_step(double un, double an, double work) {
  if (!(work > 0.0)) return 0.0;
  const double disc = un * un + 2.0 * an * work;
  if (disc < 0.0) return kInfinity;
  const double denominator = un + std::sqrt(disc);
  return denominator > 0.0 ? 2.0 * work / denominator : kInfinity;
}

// The impact in contact coordinates (t1, t2, n), scaled so that |u-| = 1 and K_nn = 1: the
// impulse P, the velocity u = u- + K P and the normal work W are O(1) numbers.
class ImpulseProcess {
 public:
  ImpulseProcess(const Eigen::Matrix3d& k, const Eigen::Vector3d& u0, double mu, double e,
                 const ImpactOptions& options)
      : k_(k), u0_(u0), mu_(mu), e_(e), options_(options) {
    if (mu_ > 0.0) {
      classify_zero_slip();
      bound_slip_turn();
    }
  }

  void run() {
    if (mu_ == 0.0) {  // frictionless: du/dp = K n throughout
      advance_linear(Eigen::Vector2d::Zero(), kInfinity);
      return;
    }
    if (sticks_before_compression_ends()) return;
    namespace odeint = boost::numeric::odeint;
    auto rhs = [this](const SlipState& y, SlipState& dy, double p) {
      const Eigen::Vector3d u = velocity(p, Eigen::Vector2d(y[0], y[1]));
      const double s = u.head<2>().norm();
      const Eigen::Vector2d dir =
          s > 0.0 ? Eigen::Vector2d(u.head<2>() / s) : Eigen::Vector2d(0, 0);
      dy[0] = -mu_ * dir.x();
      dy[1] = -mu_ * dir.y();
      dy[2] = u.z();
    };
    using Stepper = odeint::runge_kutta_fehlberg78<SlipState>;
    using Checker =
        odeint::default_error_checker<double, odeint::array_algebra, odeint::default_operations>;
// The stepper's scratch arrays are copied before their first use; GCC 12 warns about copying
// them uninitialised, which is harmless (they are written before being read).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
    odeint::controlled_runge_kutta<Stepper> controlled(
        Checker(options_.tolerance, options_.tolerance));
#pragma GCC diagnostic pop
    Stepper plain;
    // One plain step of length d from (y0, p0): the event functions are evaluated on these
    // re-steps, as accurate as the accepted step itself.
    auto step_from = [&](const SlipState& y0, double p0, double d) {
      SlipState y;
      plain.do_step(rhs, y0, p0, y, d);
      return y;
    };
    // The crossing of a rising event on the accepted step from (y_old, p_old) to (y_end, p_end),
    // where it has happened: the samples between are plain re-steps from y_old, and
    // rising_root's Newton uses the events' closed-form slopes. Returns p at the crossing (the
    // side where the event has happened) and sets *y_at to the state there (the sample itself,
    // not stepped again).
    auto locate = [&](auto&& event, const SlipState& y_old, double p_old, const SlipState& y_end,
                      double p_end, SlipState* y_at) {
      const double length = p_end - p_old;
      SlipState y_hi = y_end;
      auto sample = [&](double d) {
        const SlipState yd = step_from(y_old, p_old, d);
        const RootSample r = event(yd, p_old + d);
        if (r.value >= 0.0) y_hi = yd;
        return r;
      };
      // The accepted step is the sample at its end (the event has happened there).
      const RootSample at_start = event(y_old, p_old), at_end = event(y_end, p_end);
      if (at_end.value == 0.0 || !(length > 0.0) || !(at_start.value < 0.0)) {
        *y_at = y_end;
        return p_end;
      }
      const double at = rising_root(sample, 0.0, at_start, length, at_end.value);
      *y_at = y_hi;
      return at < length ? p_old + at : p_end;
    };
    // u_n and its rate du_n/dp = K_n . (dP_t/dp, 1), dP_t/dp = -mu u_t / |u_t|.
    auto normal_velocity = [&](const SlipState& y, double p) {
      const Eigen::Vector3d u = velocity(p, Eigen::Vector2d(y[0], y[1]));
      const double s = u.head<2>().norm();
      const Eigen::Vector2d rate =
          s > 0.0 ? Eigen::Vector2d(-mu_ * u.head<2>() / s) : Eigen::Vector2d(0, 0);
      return RootSample{u.z(), k_(2, 2) + k_(2, 0) * rate.x() + k_(2, 1) * rate.y()};
    };
    // W - W_target and its rate dW/dp = u_n.
    auto work_left = [&](const SlipState& y, double p) {
      return RootSample{y[2] - w_target_, velocity(p, Eigen::Vector2d(y[0], y[1])).z()};
    };

    double h = 1e-2;
    for (;;) {
      if (steps_ + rejected_ >= options_.max_steps) {
        // The budget is spent (every pass above counts): the rest of the impact without
        // friction, closed form. It only stops short of the law's dissipation, never adds energy.
        finish_frictionless();
        return;
      }
      const Eigen::Vector3d u = velocity(p_, pt_);
      const Eigen::Vector2d ut = u.head<2>();
      const double s = ut.norm();
      if (s <= kSnapPerTolerance * options_.tolerance) {
        // Onto u_t = 0 exactly: the tangential impulse that zeroes u_t at this p (a change of
        // order kSnap / K_tt), then stick or re-slip, both straight phases to the end.
        pt_ -= k_.topLeftCorner<2, 2>().ldlt().solve(ut);
        stuck_ = can_stick_;
        advance_linear(can_stick_ ? stick_rate_ : Eigen::Vector2d(-mu_ * ray()), kInfinity);
        return;
      }
      // The slip has slowed enough that it provably stops before compression ends: the
      // plastic full stop in closed form from here (the end the integration would reach).
      if (sticks_before_compression_ends()) return;
      const Eigen::Vector2d dir = ut / s;
      // The slip's direction provably stays constant to the tolerance until the impact ends:
      // the rest is a straight line, closed form.
      if (straight_to_tolerance(s, remaining_impulse_bound(u.z()))) {
        straight_slip_ = true;
        advance_linear(-mu_ * dir, kInfinity);
        return;
      }
      const Eigen::Vector2d accel =
          k_.topRightCorner<2, 1>() - mu_ * k_.topLeftCorner<2, 2>() * dir;
      const double s_rate = dir.dot(accel);
      const double to_zero = s_rate < 0.0 ? s / -s_rate : kInfinity;
      // On a ray the slip direction stays fixed and the rest of the slip is a straight line,
      // closed form; near u_t = 0 rays attract the slip and integrating them is stiff (steps
      // ~ |u_t|). Closing in on u_t = 0 the direction still turns by about turn / |s_rate| on
      // the way; moving out it settles on the unique re-slip ray. The switch is taken when
      // |u_t| times that turn is below kRay.
      const double turn = std::abs(dir.x() * accel.y() - dir.y() * accel.x());
      if (s_rate < 0.0 && s * turn <= kRay * -s_rate) {
        if (advance_linear(-mu_ * dir, to_zero)) return;
        ++steps_;
        continue;  // now at u_t ~ 0: snapped on the next pass
      }
      if (s_rate > 0.0 && !can_stick_ && s * (dir - ray()).norm() <= kRay) {
        advance_linear(-mu_ * ray(), kInfinity);
        return;
      }
      if (s <= kApproach && s_rate < 0.0) {
        if (advance_linear(-mu_ * dir, to_zero)) return;
        ++steps_;
        continue;
      }
      h = std::min(h, 0.9 * to_zero);  // approach u_t = 0 geometrically, never through it
      // A plastic impact: aim the step at the point where the rest of compression is short enough
      // to be straight to the tolerance (the check above then ends it in closed form on the next
      // pass, instead of a search for the crossing on re-steps): u_n = -r L / 2 by u_n's present
      // rate, L the straight length with delta = tolerance (straight_to_tolerance, s_min ~ s).
      if (e_ == 0.0 && !compressed_ && options_.straight_slip && turn_rate_ > 0.0 &&
          normal_rate_min_ > 0.0) {
        const double rate = k_(2, 2) + k_.bottomLeftCorner<1, 2>().dot(-mu_ * dir);
        const double straight =
            std::sqrt(2.0 * s * options_.tolerance * normal_rate_min_ /
                      (mu_ * turn_rate_ * std::max(normal_rate_min_, k_trace_)));
        const double aim = (-0.5 * normal_rate_min_ * straight - u.z()) / rate;
        if (aim > 0.0) h = std::min(h, aim);
      }
      const SlipState y_old{pt_.x(), pt_.y(), w_};
      const double p_old = p_;
      SlipState y = y_old;
      double p = p_old;
      if (controlled.try_step(rhs, y, p, h) == odeint::fail) {
        ++rejected_;
        continue;
      }
      if (!(p > p_old)) {  // the step is below p's resolution: no progress is possible
        finish_frictionless();
        return;
      }
      const Eigen::Vector3d u_new = velocity(p, Eigen::Vector2d(y[0], y[1]));
      if (u_new.head<2>().dot(ut) <= 0.0) {  // reached or crossed u_t = 0: shorter step
        h = 0.5 * (p - p_old);
        ++rejected_;
        continue;
      }
      ++steps_;
      // Closing on u_t = 0 the step the tolerance allows shrinks with the slip speed (the
      // direction turns at a rate ~ 1 / s): scale the controller's proposal by the speed's fall,
      // or it grows each accepted step and every other try is rejected (measured: 297 k
      // rejections against 1.03 M accepted steps in the cluster scene).
      const double s_new = u_new.head<2>().norm();
      if (s_new < s) h *= s_new / s;
      if (!compressed_ && u_new.z() >= 0.0) {
        SlipState y_at;
        const double p_at = locate(normal_velocity, y_old, p_old, y, p, &y_at);
        commit(y_at, p_at);
        end_compression();
        if (finished_) return;
        continue;
      }
      if (compressed_ && y[2] >= w_target_) {
        SlipState y_at;
        const double p_at = locate(work_left, y_old, p_old, y, p, &y_at);
        commit(y_at, p_at);
        finished_ = true;
        return;
      }
      commit(y, p);
    }
  }

  Eigen::Vector3d impulse() const { return Eigen::Vector3d(pt_.x(), pt_.y(), p_); }
  Eigen::Vector3d compression_impulse() const {
    return Eigen::Vector3d(pt_compression_.x(), pt_compression_.y(), p_compression_);
  }
  bool stuck() const { return stuck_; }
  // True when run() took the plastic full stop in closed form (no slip integration).
  bool closed_form_stop() const { return closed_form_stop_; }
  // True when run() ended (part of) the slip as a straight line (straight_to_tolerance).
  bool straight_slip() const { return straight_slip_; }
  bool stuck_at_compression() const { return stuck_at_compression_; }
  int steps() const { return steps_; }
  bool frictionless_fallback() const { return fallback_; }

 private:
  Eigen::Vector3d velocity(double p, const Eigen::Vector2d& pt) const {
    return u0_ + k_ * Eigen::Vector3d(pt.x(), pt.y(), p);
  }

  void commit(const SlipState& y, double p) {
    pt_ = Eigen::Vector2d(y[0], y[1]);
    w_ = y[2];
    p_ = p;
  }

  // What happens at u_t = 0 (the same all through the impact, K being constant): stick when
  // the friction cone allows the impulse rate that keeps u_t = 0, else slip again along the ray.
  void classify_zero_slip() {
    const Eigen::Matrix2d ktt = k_.topLeftCorner<2, 2>();
    const Eigen::Vector2d ktn = k_.topRightCorner<2, 1>();
    stick_rate_ = -ktt.ldlt().solve(ktn);
    can_stick_ = stick_rate_.norm() <= mu_;
  }

  // The re-slip direction when the contact cannot stick, computed when first asked for (most
  // impacts never ask: it costs an eigensolve and a root search).
  const Eigen::Vector2d& ray() {
    if (!ray_known_) {
      find_ray();
      ray_known_ = true;
    }
    return ray_;
  }

  void find_ray() {
    const Eigen::Matrix2d ktt = k_.topLeftCorner<2, 2>();
    const Eigen::Vector2d ktn = k_.topRightCorner<2, 1>();
    // K_tn = (l 1 + mu K_tt) s with |s| = 1: in K_tt's eigenbasis |s(l)| falls strictly from
    // |K_tt^-1 K_tn| / mu > 1 at l = 0 to <= 1 at l = |K_tn|, so l is unique.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(ktt);
    const Eigen::Vector2d kappa = eigen.eigenvalues();
    const Eigen::Vector2d kt = eigen.eigenvectors().transpose() * ktn;
    auto excess = [&](double l) {
      const double s0 = kt.x() / (mu_ * kappa.x() + l), s1 = kt.y() / (mu_ * kappa.y() + l);
      return s0 * s0 + s1 * s1 - 1.0;
    };
    const double hi = ktn.norm();
    if (!std::isfinite(excess(0.0)) || !(excess(hi) <= 0.0)) {
      // mu so small that mu K_tt underflows next to K_tn: the ray is K_tn's direction (the
      // limit l -> |K_tn|).
      ray_ = ktn / hi;
      return;
    }
    std::uintmax_t iterations = 100;
    const auto bracket = boost::math::tools::toms748_solve(
        excess, 0.0, hi, excess(0.0), excess(hi),
        boost::math::tools::eps_tolerance<double>(std::numeric_limits<double>::digits - 2),
        iterations);
    const double l = 0.5 * (bracket.first + bracket.second);
    const Eigen::Vector2d s_eigen(kt.x() / (mu_ * kappa.x() + l), kt.y() / (mu_ * kappa.y() + l));
    ray_ = (eigen.eigenvectors() * s_eigen).normalized();
  }

  // A plastic impact (e* = 0) whose slip provably stops before compression ends, and can stick,
  // ends with u+ = 0: P = -K^-1 u-, one 3x3 solve instead of the slip integration. Proof: while
  // slipping along d (|d| = 1, dP_t/dp = -mu d) the slip speed s = |u_t| changes at
  // ds/dp = d.(K_tn - mu K_tt d) <= |K_tn| - mu lmin(K_tt) =: -r, and the normal velocity at
  // du_n/dp = 1 - mu K_nt.d <= 1 + mu |K_tn|. With r > 0 the slip has stopped by p_s <= s0 / r,
  // and u_n < 0 (compression goes on) for p < -u_n- / (1 + mu |K_tn|) =: p_lo. If s0 / r < p_lo
  // the slip stops during compression; the contact then sticks (can_stick_: the rate
  // -K_tt^-1 K_tn keeping u_t = 0 lies in the cone) and stays stuck, u_n rising at the Schur
  // complement K_nn - K_nt K_tt^-1 K_tn > 0, until u_n = 0: the end for e* = 0, with u = 0. The
  // cone holds: the slip phase adds |dP_t| = mu dp, the stuck phase |dP_t| <= mu dp. Energy:
  // dE = u-.P + P.K P / 2 = -u-.K^-1 u- / 2 < 0. The slip integration reaches the same P up to
  // its tolerance (it snaps onto u_t = 0, then sticks along the same straight line). A computed
  // P that round-off put outside the cone goes to the integration instead. The same holds from
  // any point of the slip integration before compression ends (s0 and u_n- then the slip speed
  // and normal velocity there; the slip so far added |dP_t| = mu dp): the end is again u+ = 0,
  // P = -K^-1 u-, so a slip that closes on u_t = 0 slowly (steps shrinking with |u_t|) is cut
  // short as soon as the bound holds.
  bool sticks_before_compression_ends() {
    if (e_ != 0.0 || !can_stick_) return false;
    const double ktn = ktn_norm_;
    const double r = mu_ * ktt_lambda_min_ - ktn;
    const Eigen::Vector3d u = velocity(p_, pt_);
    const double s0 = u.head<2>().norm(), un0 = u.z();
    if (!(r > 0.0) || !(un0 < 0.0)) return false;
    if (!(s0 * (1.0 + mu_ * ktn) < -un0 * r)) return false;  // s0 / r < p_lo
    const Eigen::Vector3d p = -k_.ldlt().solve(u0_);
    if (!p.allFinite() || !(p.z() > 0.0) || !(p.head<2>().norm() <= mu_ * p.z())) return false;
    pt_ = p.head<2>();
    p_ = p.z();
    w_ = 0.0;  // not needed for e* = 0: the impact ends at the end of compression
    compressed_ = finished_ = stuck_ = stuck_at_compression_ = true;
    p_compression_ = p_;
    pt_compression_ = pt_;
    closed_form_stop_ = true;
    return true;
  }

  // K_tt's eigenvalues and the rates that bound how fast the slip can turn and slow
  // (straight_to_tolerance, sticks_before_compression_ends).
  void bound_slip_turn() {
    const Eigen::Matrix2d ktt = k_.topLeftCorner<2, 2>();
    ktn_norm_ = k_.topRightCorner<2, 1>().norm();
    const double half_trace = 0.5 * (ktt(0, 0) + ktt(1, 1));
    const double half_spread = std::hypot(0.5 * (ktt(0, 0) - ktt(1, 1)), ktt(0, 1));
    ktt_lambda_min_ = half_trace - half_spread;
    turn_rate_ = ktn_norm_ + mu_ * half_spread;
    slow_rate_ = ktn_norm_ + mu_ * (half_trace + half_spread);
    normal_rate_min_ = k_(2, 2) - mu_ * ktn_norm_;
    k_trace_ = k_.trace();
  }

  // An upper bound of the normal impulse from here (normal velocity un, work w_) to the end of
  // the impact, along any slip direction: u_n rises at du_n/dp = K_nn - mu K_nt.d >= r :=
  // K_nn - mu |K_tn| (Stronge, "Impact Mechanics", 2000, ch. 5: the impulse-space process), so
  // compression ends within -u_n / r; its work W_c is at least W - u_n^2 / (2 r) (u_n lies between
  // u_n + r q and 0); restitution needs the work e*^2 |W_c| with u_n >= r q, so it ends within
  // sqrt(2 e*^2 |W_c| / r); once compressed, the work left R within sqrt(2 R / r).
  double remaining_impulse_bound(double un) const {
    const double r = normal_rate_min_;
    if (!(r > 0.0)) return kInfinity;
    if (compressed_) return std::sqrt(2.0 * std::max(0.0, w_target_ - w_) / r);
    const double compression = std::max(0.0, -un) / r;
    const double work_c = std::abs(w_) + 0.5 * un * un / r;
    return compression + e_ * std::sqrt(2.0 * work_c / r);
  }

  // True when the slip from here (speed s = |u_t| > 0, direction d0) keeps its direction to the
  // tolerance for the next `length` of normal impulse, so that the slip is the straight line
  // u(p) = u + p K (-mu d0, 1) to the tolerance (advance_linear). Bound (Stronge 2000, ch. 5,
  // for the process du/dp = K (-mu d, 1), d = u_t / |u_t|): with a = du_t/dp = K_tn - mu K_tt d,
  //  - the slip speed falls at most at ds/dp = d.a >= -(|K_tn| + mu lmax(K_tt)) =: -c_s, so
  //    s >= s_min := s - c_s length > 0 throughout: the slip never stops;
  //  - the direction turns at |dd/dp| = |(1 - d d^T) a| / s <= c_t / s_min with c_t :=
  //    |K_tn| + mu (lmax - lmin) / 2 (the part of K_tt d across d is at most half K_tt's spread),
  //    so |d(q) - d0| <= c_t q / s_min;
  //  - the tangential impulse P_t = -mu int d dq then leaves the line by at most
  //    delta := mu c_t length^2 / (2 s_min); the velocity by |K| delta <= tr(K) delta; the work
  //    W = int u_n dq by |K_tn| length delta; the end of compression (u_n = 0, crossed at a rate
  //    >= r = K_nn - mu |K_tn|) moves by tr(K) delta / r; the end of restitution by the work's
  //    deviation over u_n there, as it would with the integration's own error.
  // All below the tolerance: the line is as accurate as the integration. It cannot add energy:
  // dE = W - mu int u_t.d0 dq, with W <= 0 at the end and u_t.d0 >= s_min > 0 on the line.
  bool straight_to_tolerance(double s, double length) const {
    if (!options_.straight_slip || !(normal_rate_min_ > 0.0) || !(length < kInfinity)) {
      return false;
    }
    const double s_min = s - slow_rate_ * length;
    if (!(s_min > 0.0)) return false;
    const double delta = mu_ * turn_rate_ * length * length / (2.0 * s_min);
    const double spread = std::max({1.0, k_trace_ / normal_rate_min_, ktn_norm_ * length});
    return delta * spread <= options_.tolerance;
  }

  // The fallback: the impact goes on from where it is along K n (no tangential impulse) to the
  // same end conditions. The energy balance dE = W - mu int |u_t| dp keeps its sign: the normal
  // work still ends at (1 - e*^2) W_c and the friction work done so far is dissipative.
  void finish_frictionless() {
    fallback_ = true;
    stuck_ = false;
    advance_linear(Eigen::Vector2d::Zero(), kInfinity);
  }

  void move_linear(const Eigen::Vector2d& xi, double delta) {
    const double un = velocity(p_, pt_).z();
    const double an = k_.row(2).dot(Eigen::Vector3d(xi.x(), xi.y(), 1.0));
    w_ += un * delta + 0.5 * an * delta * delta;
    p_ += delta;
    pt_ += xi * delta;
  }

  void end_compression() {
    compressed_ = true;
    w_target_ = (1.0 - e_ * e_) * w_;
    p_compression_ = p_;
    pt_compression_ = pt_;
    stuck_at_compression_ = stuck_;
    if (e_ == 0.0) finished_ = true;
  }

  // Along a constant tangential impulse rate xi for at most delta_max of normal impulse, through
  // the end of compression; true when the impact has ended.
  bool advance_linear(const Eigen::Vector2d& xi, double delta_max) {
    const double an = k_.row(2).dot(Eigen::Vector3d(xi.x(), xi.y(), 1.0));
    // A phase that would never end (a jam: the approach or the rebound never completes along
    // xi) goes on frictionless instead, where an = K_nn = 1 ends both.
    auto jammed = [&](double length) {
      return length == kInfinity && delta_max == kInfinity && xi != Eigen::Vector2d::Zero();
    };
    for (;;) {
      const double un = velocity(p_, pt_).z();
      if (!compressed_) {
        const double dc = un >= 0.0 ? 0.0 : (an > 0.0 ? -un / an : kInfinity);
        if (jammed(dc)) {
          finish_frictionless();
          return true;
        }
        if (dc > delta_max) {
          move_linear(xi, delta_max);
          return false;
        }
        move_linear(xi, dc);
        delta_max -= dc;
        end_compression();
        if (finished_) return true;
        continue;
      }
      const double dr = restitution_step(un, an, w_target_ - w_);
      if (jammed(dr)) {
        finish_frictionless();
        return true;
      }
      if (dr > delta_max) {
        move_linear(xi, delta_max);
        return false;
      }
      move_linear(xi, dr);
      finished_ = true;
      return true;
    }
  }

  Eigen::Matrix3d k_;
  Eigen::Vector3d u0_;
  double mu_, e_;
  ImpactOptions options_;
  double p_ = 0.0, w_ = 0.0, w_target_ = 0.0, p_compression_ = 0.0;
  Eigen::Vector2d pt_ = Eigen::Vector2d::Zero(), pt_compression_ = Eigen::Vector2d::Zero();
  bool compressed_ = false, finished_ = false, stuck_ = false, stuck_at_compression_ = false;
  bool can_stick_ = true;
  Eigen::Vector2d stick_rate_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d ray_ = Eigen::Vector2d::Zero();  // the re-slip direction when !can_stick_
  bool ray_known_ = false;                         // ray_ computed (ray())
  int steps_ = 0, rejected_ = 0;
  bool fallback_ = false;
  bool closed_form_stop_ = false;
  bool straight_slip_ = false;
  // bound_slip_turn(): |K_tn|, lmin(K_tt), the bounds c_t, c_s, r of straight_to_tolerance, tr(K).
  double ktn_norm_ = 0.0, ktt_lambda_min_ = 0.0, turn_rate_ = 0.0, slow_rate_ = 0.0;
  double normal_rate_min_ = 0.0, k_trace_ = 0.0;
};

// The law only dissipates; the numerical slip integration and the snap onto u_t = 0 can leave
// a gain of round-off size where the exact dE is 0. Shortening the impulse along itself removes
// it: dE(k P) = k a + k^2 b / 2 with a = P . u- < 0, b = P^T K P > 0 is 0 at k = -2a/b < 1 and
// negative below, so this can only remove energy. Returns the scale to apply to P.
inline double energy_safe_scale(const Eigen::Vector3d& p, const Eigen::Vector3d& u,
                                const Eigen::Matrix3d& k) {
  const double a = p.dot(u), b = p.dot(k * p);
  if (a + 0.5 * b > 0.0 && b > 0.0) return std::max(0.0, -2.0 * a / b);
  return 1.0;
}

}  // namespace impulse_process
}  // namespace virtual_go
