// Independent closed-form motion for the node tests, written from docs/physics.md ("Flight in
// closed form") and filled from the messages the node publishes (StoneInfo, StoneEvent): shares no
// code with the core. Translation x0 + v0 t + g t^2 / 2; constant_omega q(t) = exp(t w) q0;
// rigid_body (axisymmetric, I1 = I2) q(t) = exp(t L / I1) q0 exp(-Omega t e_z), Omega = (I3 - I1)
// w3 / I1.
#pragma once

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Transform.h>
#include <geometry_msgs/Twist.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "virtual_go/StoneEvent.h"
#include "virtual_go/StoneInfo.h"

namespace vgtest {

inline Eigen::Vector3d vec(const geometry_msgs::Vector3& v) { return {v.x, v.y, v.z}; }
inline Eigen::Vector3d vec(const geometry_msgs::Point& p) { return {p.x, p.y, p.z}; }
inline Eigen::Quaterniond quat(const geometry_msgs::Quaternion& q) {
  return Eigen::Quaterniond(q.w, q.x, q.y, q.z);
}

// Rotation by |v| about v / |v|.
inline Eigen::Quaterniond exp_map(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  if (angle == 0.0) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, v / angle));
}

// Sign-insensitive angle between two orientations (docs/physics.md, "Measuring error").
inline double angle_between(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  const Eigen::Quaterniond d = a.conjugate() * b.normalized();
  return 2.0 * std::atan2(d.vec().norm(), std::abs(d.w()));
}

struct MotionState {
  Eigen::Vector3d position, velocity, angular_velocity_world;
  Eigen::Quaterniond orientation;
};

class ClosedForm {
 public:
  // The motion from a segment start: pose and world twist at time 0.
  ClosedForm(const virtual_go::StoneInfo& info, const geometry_msgs::Pose& pose,
             const geometry_msgs::Twist& twist)
      : x0_(vec(pose.position)),
        v0_(vec(twist.linear)),
        g_(vec(info.gravity)),
        q0_(quat(pose.orientation).normalized()),
        w0_(vec(twist.angular)),
        i1_(info.principal_moments.x),
        i3_(info.principal_moments.z),
        rigid_(info.model == "rigid_body") {
    const Eigen::Matrix3d r = q0_.toRotationMatrix();
    const Eigen::Vector3d moments(i1_, i1_, i3_);
    const Eigen::Vector3d w_body = r.transpose() * w0_;
    l_world_ = r * moments.cwiseProduct(w_body);
    body_rate_ = rigid_ ? (i3_ - i1_) * w_body.z() / i1_ : 0.0;
  }
  static ClosedForm from_info(const virtual_go::StoneInfo& info) {
    return ClosedForm(info, info.initial_pose, info.initial_twist);
  }
  static ClosedForm from_event(const virtual_go::StoneInfo& info,
                               const virtual_go::StoneEvent& event) {
    return ClosedForm(info, event.pose, event.twist);
  }

  MotionState at(double t) const {
    MotionState s;
    s.position = x0_ + v0_ * t + 0.5 * g_ * t * t;
    s.velocity = v0_ + g_ * t;
    if (rigid_) {
      s.orientation =
          exp_map(t * l_world_ / i1_) * q0_ * exp_map(Eigen::Vector3d(0, 0, -body_rate_ * t));
      const Eigen::Vector3d axis = s.orientation * Eigen::Vector3d::UnitZ();
      s.angular_velocity_world = l_world_ / i1_ - body_rate_ * axis;
    } else {
      s.orientation = exp_map(t * w0_) * q0_;
      s.angular_velocity_world = w0_;
    }
    return s;
  }

 private:
  Eigen::Vector3d x0_, v0_, g_;
  Eigen::Quaterniond q0_;
  Eigen::Vector3d w0_;
  double i1_, i3_;
  bool rigid_;
  Eigen::Vector3d l_world_;
  double body_rate_;
};

}  // namespace vgtest
