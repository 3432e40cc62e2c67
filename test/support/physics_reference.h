// Independent references for the core tests, written from the formulas in docs/physics.md and the
// textbook equations, never by calling the code under test: quaternion algebra on plain
// 4-vectors, the closed-form torque-free axisymmetric top, and a classical RK4 integration of
// Euler's equations in the body frame. Tests compare the core against these.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace vgtest {

// (w, x, y, z); kept apart from Eigen::Quaterniond so the reference shares no code with the core.
using Quat = Eigen::Vector4d;

inline Quat qmul(const Quat& p, const Quat& q) {  // Hamilton product
  return Quat(p[0] * q[0] - p[1] * q[1] - p[2] * q[2] - p[3] * q[3],
              p[0] * q[1] + p[1] * q[0] + p[2] * q[3] - p[3] * q[2],
              p[0] * q[2] - p[1] * q[3] + p[2] * q[0] + p[3] * q[1],
              p[0] * q[3] + p[1] * q[2] - p[2] * q[1] + p[3] * q[0]);
}
inline Quat qconj(const Quat& q) { return Quat(q[0], -q[1], -q[2], -q[3]); }
inline Quat from_eigen(const Eigen::Quaterniond& q) { return Quat(q.w(), q.x(), q.y(), q.z()); }
inline Eigen::Quaterniond to_eigen(const Quat& q) {
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
}

// q v q* for a unit q.
inline Eigen::Vector3d rotate(const Quat& q, const Eigen::Vector3d& v) {
  return qmul(qmul(q, Quat(0.0, v.x(), v.y(), v.z())), qconj(q)).tail<3>();
}

// Rotation by |v| about v / |v|.
inline Quat axis_angle(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  if (angle == 0.0) return Quat(1.0, 0.0, 0.0, 0.0);
  const Eigen::Vector3d axis = v / angle;
  const double s = std::sin(0.5 * angle);
  return Quat(std::cos(0.5 * angle), s * axis.x(), s * axis.y(), s * axis.z());
}

// Geodesic angle between orientations (docs/physics.md, "Measuring error"), sign-insensitive.
inline double angle_between(const Quat& p, const Quat& q) {
  const Quat d = qmul(qconj(p), q);
  return 2.0 * std::atan2(d.tail<3>().norm(), std::abs(d[0]));
}
inline double angle_between(const Eigen::Quaterniond& p, const Eigen::Quaterniond& q) {
  return angle_between(from_eigen(p), from_eigen(q));
}

// Torque-free axisymmetric top (I1 = I2), closed form from docs/physics.md ("Flight in closed
// form"): q(t) = exp(t L / I1) q0 exp(-Omega t e_z), Omega = (I3 - I1) omega3 / I1.
struct AxisymmetricTop {
  double i1, i3;
  Quat q0;
  Eigen::Vector3d l_world;

  double omega3() const { return rotate(qconj(q0), l_world).z() / i3; }
  double body_precession_rate() const { return (i3 - i1) * omega3() / i1; }
  Quat orientation_at(double t) const {
    return qmul(qmul(axis_angle(t * l_world / i1), q0),
                axis_angle(Eigen::Vector3d(0.0, 0.0, -body_precession_rate() * t)));
  }
};

// Torque-free rigid body, any principal moments, state in the body frame: Euler's equations
// I dw/dt = (I w) x w and dq/dt = 1/2 q (0, w), integrated by classical RK4 with a fine step.
struct EulerEquationsReference {
  Eigen::Vector3d inertia;  // principal moments, body x y z

  struct State {
    Quat q;
    Eigen::Vector3d omega_body;
  };

  State derivative(const State& s) const {
    const Eigen::Vector3d w = s.omega_body;
    State d;
    d.q = 0.5 * qmul(s.q, Quat(0.0, w.x(), w.y(), w.z()));
    d.omega_body = (inertia.cwiseProduct(w)).cross(w).cwiseQuotient(inertia);
    return d;
  }

  // Integrates from s over t with n equal steps.
  State integrate(State s, double t, int n) const {
    const double h = t / n;
    auto axpy = [](const State& a, double k, const State& b) {
      return State{a.q + k * b.q, a.omega_body + k * b.omega_body};
    };
    for (int i = 0; i < n; ++i) {
      const State k1 = derivative(s);
      const State k2 = derivative(axpy(s, 0.5 * h, k1));
      const State k3 = derivative(axpy(s, 0.5 * h, k2));
      const State k4 = derivative(axpy(s, h, k3));
      s.q += (h / 6.0) * (k1.q + 2.0 * k2.q + 2.0 * k3.q + k4.q);
      s.omega_body +=
          (h / 6.0) * (k1.omega_body + 2.0 * k2.omega_body + 2.0 * k3.omega_body + k4.omega_body);
    }
    s.q.normalize();
    return s;
  }
};

// Least-squares slope of log(error) against log(dt): the measured convergence order.
inline double fitted_order(const std::vector<double>& dts, const std::vector<double>& errors) {
  const int n = static_cast<int>(dts.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int i = 0; i < n; ++i) {
    const double x = std::log(dts[i]), y = std::log(errors[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Runs f, expects exception E, returns its what() ("" and a test failure if none was thrown).
template <class E>
std::string what_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    return "";
  }
  ADD_FAILURE() << "no exception thrown";
  return "";
}

}  // namespace vgtest
