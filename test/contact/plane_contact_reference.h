// Independent references for the plane-contact tests, written from the physics and sharing no
// code with the contact module: a planar model of a lens on its bottom cap (coordinates x_G and
// the tilt theta, Newton-Euler in the x-z plane, Coulomb friction and a rolling-resistance couple
// as 1-D set-valued laws, fixed-step RK4 with events located by bisection of the step), and
// energy-integral quadratures for rocking periods.
#pragma once

#include <Eigen/Dense>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <functional>
#include <vector>

namespace plane_contact_reference {

// A lens rocking and sliding in the x-z plane on its bottom cap (plane z = 0), tilt theta about
// +y (axis b = (sin theta, 0, cos theta)). z_G = R - d cos(theta); the contact point is
// r = (d sin(theta), d cos(theta) - R) from G; the slip velocity u = v_x + omega r_z.
class PlanarCap {
 public:
  struct State {
    double x = 0, theta = 0, vx = 0, omega = 0;
  };
  enum class Tangential { slip, stick };
  enum class Rolling { free, rolling, stuck };
  struct Mode {
    Tangential tangential = Tangential::slip;
    double slip_sign = 1;  // direction of u while slipping
    Rolling rolling = Rolling::free;
    double roll_sign = 1;  // direction of omega while rolling against l_r
  };
  struct Forces {
    double ax, alpha, normal, friction, couple;
  };

  PlanarCap(double m, double i1, double big_r, double d, double g, double mu, double l_r)
      : m_(m), i1_(i1), r_(big_r), d_(d), g_(g), mu_(mu), l_r_(l_r) {}

  double slip(const State& s) const { return s.vx + s.omega * (d_ * std::cos(s.theta) - r_); }

  // Unknowns (a_x, alpha, N, F, tau): m a_x = F; m z'' = N - m g; I1 alpha = r_z F - r_x N + tau;
  // plus one closure each for the tangential and the rolling law.
  Forces forces(const State& s, const Mode& mode) const {
    const double st = std::sin(s.theta), ct = std::cos(s.theta);
    const double rx = d_ * st, rz = d_ * ct - r_;
    Eigen::Matrix<double, 5, 5> a = Eigen::Matrix<double, 5, 5>::Zero();
    Eigen::Matrix<double, 5, 1> b = Eigen::Matrix<double, 5, 1>::Zero();
    a(0, 0) = m_;
    a(0, 3) = -1;
    // z'' = d (cos theta omega^2 + sin theta alpha)
    a(1, 1) = m_ * d_ * st;
    a(1, 2) = -1;
    b(1) = -m_ * g_ - m_ * d_ * ct * s.omega * s.omega;
    a(2, 1) = i1_;
    a(2, 3) = -rz;
    a(2, 2) = rx;
    a(2, 4) = -1;
    if (mode.tangential == Tangential::slip) {
      a(3, 3) = 1;
      a(3, 2) = mu_ * mode.slip_sign;
    } else {  // u' = a_x + alpha r_z + omega r_z' = 0, r_z' = -d sin(theta) omega
      a(3, 0) = 1;
      a(3, 1) = rz;
      b(3) = d_ * st * s.omega * s.omega;
    }
    if (mode.rolling == Rolling::free) {
      a(4, 4) = 1;
    } else if (mode.rolling == Rolling::rolling) {
      a(4, 4) = 1;
      a(4, 2) = l_r_ * mode.roll_sign;
    } else {
      a(4, 1) = 1;
    }
    const Eigen::Matrix<double, 5, 1> x = a.fullPivLu().solve(b);
    return {x(0), x(1), x(2), x(3), x(4)};
  }

  State derivative(const State& s, const Mode& mode) const {
    const Forces f = forces(s, mode);
    return {s.vx, s.omega, f.ax, f.alpha};
  }

  State rk4(const State& s, const Mode& mode, double h) const {
    auto add = [](const State& a, const State& k, double f) {
      return State{a.x + f * k.x, a.theta + f * k.theta, a.vx + f * k.vx, a.omega + f * k.omega};
    };
    const State k1 = derivative(s, mode);
    const State k2 = derivative(add(s, k1, h / 2), mode);
    const State k3 = derivative(add(s, k2, h / 2), mode);
    const State k4 = derivative(add(s, k3, h), mode);
    State out = s;
    out.x += h / 6 * (k1.x + 2 * k2.x + 2 * k3.x + k4.x);
    out.theta += h / 6 * (k1.theta + 2 * k2.theta + 2 * k3.theta + k4.theta);
    out.vx += h / 6 * (k1.vx + 2 * k2.vx + 2 * k3.vx + k4.vx);
    out.omega += h / 6 * (k1.omega + 2 * k2.omega + 2 * k3.omega + k4.omega);
    return out;
  }

  // Event function of the mode: positive while it holds.
  double event(const State& s, const Mode& mode) const {
    const Forces f = forces(s, mode);
    double g = f.normal;
    if (mode.tangential == Tangential::slip) {
      g = std::min(g, slip(s) * mode.slip_sign);
    } else if (mu_ > 0) {
      g = std::min(g, (mu_ * f.normal - std::abs(f.friction)) / (mu_ * m_ * g_));
    }
    if (mode.rolling == Rolling::rolling) {
      g = std::min(g, s.omega * mode.roll_sign);
    } else if (mode.rolling == Rolling::stuck) {
      g = std::min(g, (l_r_ * f.normal - std::abs(f.couple)) / (l_r_ * m_ * g_));
    }
    return g;
  }

  // The mode at a state where the tangential or rolling motion is zero (or a bound is reached).
  Mode choose(const State& s, Mode mode, bool tangential_zero, bool rolling_zero) const {
    if (mu_ > 0 && tangential_zero) mode.tangential = Tangential::stick;
    if (l_r_ > 0 && rolling_zero) mode.rolling = Rolling::stuck;
    for (int round = 0; round < 2; ++round) {
      const Forces f = forces(s, mode);
      if (mode.tangential == Tangential::stick && std::abs(f.friction) > mu_ * f.normal) {
        mode.tangential = Tangential::slip;
        mode.slip_sign = f.friction > 0 ? -1 : 1;
        continue;
      }
      if (mode.rolling == Rolling::stuck && std::abs(f.couple) > l_r_ * f.normal) {
        mode.rolling = Rolling::rolling;
        mode.roll_sign = f.couple > 0 ? -1 : 1;
        continue;
      }
      break;
    }
    return mode;
  }

  struct Event {
    double time;
    State state;
    Mode mode_before, mode_after;
  };

  // Integrates from (t0, s) with step h to t_end; calls sample(t, state) after every step.
  // Returns the mode-change events; stops at rest (all stuck, at rest) or t_end.
  std::vector<Event> run(State s, Mode mode, double t_end, double h,
                         const std::function<void(double, const State&)>& sample) const {
    std::vector<Event> events;
    double t = 0;
    while (t < t_end) {
      const double step = std::min(h, t_end - t);
      State next = rk4(s, mode, step);
      if (event(s, mode) > 0 && event(next, mode) <= 0) {
        double lo = 0, hi = step;
        for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
          const double mid = 0.5 * (lo + hi);
          (event(rk4(s, mode, mid), mode) > 0 ? lo : hi) = mid;
        }
        s = rk4(s, mode, hi);
        t += hi;
        const Forces f = forces(s, mode);
        const bool t_zero = mode.tangential == Tangential::slip && slip(s) * mode.slip_sign <= 0;
        const bool r_zero = mode.rolling == Rolling::rolling && s.omega * mode.roll_sign <= 0;
        Mode after = mode;
        if (mode.tangential == Tangential::stick && std::abs(f.friction) >= mu_ * f.normal) {
          after.tangential = Tangential::slip;
          after.slip_sign = f.friction > 0 ? -1 : 1;
        }
        if (mode.rolling == Rolling::stuck && std::abs(f.couple) >= l_r_ * f.normal) {
          after.rolling = Rolling::rolling;
          after.roll_sign = f.couple > 0 ? -1 : 1;
        }
        if (t_zero || r_zero) after = choose(s, after, t_zero, r_zero);
        if (t_zero) s.vx = -s.omega * (d_ * std::cos(s.theta) - r_);  // exactly no slip
        if (r_zero) s.omega = 0;
        events.push_back({t, s, mode, after});
        mode = after;
        sample(t, s);
        if (mode.tangential == Tangential::stick && mode.rolling == Rolling::stuck) break;
        continue;
      }
      s = next;
      t += step;
      sample(t, s);
    }
    return events;
  }

 private:
  double m_, i1_, r_, d_, g_, mu_, l_r_;
};

// Time a conservative one-degree-of-freedom oscillation between -theta0 and theta0 takes from
// the turning point theta0 to theta (0 <= theta < theta0), with kinetic energy
// 1/2 M(theta) theta'^2 and potential V (even in theta), given as the drop V(theta0) - V(theta)
// >= 0 as a function of (theta0, theta, theta0 - theta): the difference is passed without
// cancellation so that the caller can write the drop without it too.
// t = int_theta^theta0 dtheta / theta', theta = theta0 sin(phi), theta' = sqrt(2 drop / M).
// `breaks` (in (theta, theta0)) split the quadrature where V or M have a kink.
inline double time_from_turning_point(const std::function<double(double)>& inertia,
                                      const std::function<double(double, double, double)>& drop,
                                      double theta0, double theta,
                                      std::vector<double> breaks = {}) {
  auto integrand = [&](double phi) {
    const double th = theta0 * std::sin(phi);
    const double half = std::sin(M_PI / 4 - phi / 2);  // theta0 - th = 2 theta0 half^2
    return theta0 * std::cos(phi) /
           std::sqrt(2 * drop(theta0, th, 2 * theta0 * half * half) / inertia(th));
  };
  std::vector<double> edges{std::asin(theta / theta0)};
  for (double b : breaks) edges.push_back(std::asin(b / theta0));
  edges.push_back(M_PI / 2);
  double total = 0;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    total += boost::math::quadrature::gauss_kronrod<double, 61>::integrate(integrand, edges[i],
                                                                           edges[i + 1], 15, 1e-14);
  }
  return total;
}

// The period of that oscillation: four times the time from theta0 to 0.
inline double oscillation_period(const std::function<double(double)>& inertia,
                                 const std::function<double(double, double, double)>& drop,
                                 double theta0, std::vector<double> breaks = {}) {
  return 4 * time_from_turning_point(inertia, drop, theta0, 0.0, breaks);
}

}  // namespace plane_contact_reference
