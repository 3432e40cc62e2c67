#include "support/world_bags.h"

#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <tf2_msgs/TFMessage.h>
#include <virtual_go/StoneEvent.h>
#include <virtual_go/StoneInfo.h>

#include <cmath>
#include <limits>
#include <vector>

#include "support/bag_messages.h"
#include "virtual_go/go/stone.h"
#include "virtual_go/world/world.h"

namespace virtual_go_test {
namespace {

namespace vg = virtual_go;

geometry_msgs::Pose pose_msg(const vg::RigidBodyState& s) {
  return virtual_go_test::pose_msg(s.position_world, s.orientation);
}

enum class Kind { flight, contact, rest };

Kind kind_of(const std::string& reason) {
  if (reason == "slide" || reason == "roll" || reason == "rim") return Kind::contact;
  if (reason == "rest") return Kind::rest;
  return Kind::flight;
}

}  // namespace

WorldRunSummary write_world_bag(const std::string& path, const WorldRunSpec& spec) {
  const vg::Stone stone = vg::make_stone(vg::StoneSpec{});
  const vg::MotionModel model(vg::MotionModelKind::rigid_body, stone.mass_properties);
  const Eigen::Vector3d gravity(0.0, 0.0, -9.80665);
  vg::WorldConfig config(vg::MotionSetup{model, gravity}, stone.shape);
  config.board_material = config.table_material = spec.material;
  vg::World world(config, spec.initial, 0.0);

  WorldRunSummary summary;
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  const double dt_s = static_cast<double>(spec.dt_ns) * 1e-9;

  vg::StoneInfo info;
  info.header.stamp = stamp(spec.start_ns);
  info.header.frame_id = "world";
  info.world_frame = "world";
  info.stone_frame = "stone";
  info.width = stone.shape.width();
  info.height = stone.shape.height();
  info.mass = stone.mass_properties.mass();
  info.density = stone.density;
  info.principal_moments = vec_msg(stone.mass_properties.principal_moments_body());
  info.model = "rigid_body";
  info.integrator = "exact";
  info.dt = dt_s;
  info.dt_ns = spec.dt_ns;
  info.rate = 1.0 / dt_s;
  info.gravity = vec_msg(gravity);
  info.initial_pose = pose_msg(spec.initial);
  info.initial_twist.linear = vec_msg(spec.initial.velocity_world);
  info.initial_twist.angular = vec_msg(
      model.angular_velocity_world(spec.initial.orientation, spec.initial.angular_momentum_world));
  info.max_angular_velocity = 1000.0;
  info.board_enabled = true;
  info.board_size.x = config.board.size_x_m;
  info.board_size.y = config.board.size_y_m;
  info.board_size.z = config.board.thickness_m;
  info.board_restitution = info.table_restitution = spec.material.restitution;
  info.board_friction = info.table_friction = spec.material.friction;
  info.board_rolling_resistance = info.table_rolling_resistance =
      spec.material.rolling_resistance_m;
  info.board_spinning_friction = info.table_spinning_friction = spec.material.spinning_friction_m;
  info.zeno_height = config.zeno_height_m;
  bag.write("/stone/info", stamp(spec.start_ns), info, latched_header<vg::StoneInfo>());

  std::uint32_t segment = 0;
  // The stamp rule of ~events: the instant rounded down to a whole ns, the rest in time_offset.
  auto write_event = [&](double t_s, const std::string& reason, const std::string& detail,
                         const vg::RigidBodyState& s) {
    const double whole_ns = std::floor(t_s * 1e9);
    double offset = t_s - whole_ns * 1e-9;
    offset = std::min(std::max(offset, 0.0), std::nextafter(1e-9, 0.0));
    const std::int64_t ns = spec.start_ns + static_cast<std::int64_t>(whole_ns);
    vg::StoneEvent e;
    e.header.stamp = stamp(ns);
    e.header.frame_id = "world";
    e.time_offset = offset;
    e.segment = segment++;
    e.reason = reason;
    e.detail = detail;
    e.pose = pose_msg(s);
    e.twist.linear = vec_msg(s.velocity_world);
    e.twist.angular =
        vec_msg(model.angular_velocity_world(s.orientation, s.angular_momentum_world));
    e.angular_momentum = vec_msg(s.angular_momentum_world);
    bag.write("/stone/events", stamp(ns), e, latched_header<vg::StoneEvent>());
    ++summary.events;
  };
  write_event(0.0, "start", "", spec.initial);

  // Total energy, J, written here from the definition.
  auto energy = [&](const vg::RigidBodyState& s) {
    const Eigen::Vector3d omega =
        model.angular_velocity_world(s.orientation, s.angular_momentum_world);
    return 0.5 * info.mass * s.velocity_world.squaredNorm() +
           0.5 * omega.dot(s.angular_momentum_world) - info.mass * gravity.dot(s.position_world);
  };
  Kind kind = Kind::flight;
  std::size_t in_segment = 0;  // samples so far in the current segment
  double previous_energy = 0.0;
  std::vector<vg::WorldEvent> events;
  const auto steps = static_cast<std::int64_t>(std::llround(spec.duration_s / dt_s));
  for (std::int64_t n = 0; n <= steps; ++n) {
    events.clear();
    world.advance_to(static_cast<double>(n * spec.dt_ns) * 1e-9, events);
    for (const vg::WorldEvent& e : events) {
      const std::string reason = vg::world_event_kind_name(e.kind);
      write_event(e.time_s, reason, vg::world_event_detail_name(e.detail), e.state);
      kind = kind_of(reason);
      in_segment = 0;
      summary.impacts += e.kind == vg::WorldEventKind::impact;
      summary.contacts += kind == Kind::contact;
      if (e.kind == vg::WorldEventKind::rest) {
        ++summary.rests;
        summary.rest_time_s = e.time_s;
      }
    }
    vg::RigidBodyState s = world.state(0);
    const bool target = in_segment == 2 && !summary.corrupted;
    switch (spec.corruption) {
      case Corruption::none:
        break;
      case Corruption::energy_bump:
        // The speed raised until the energy lies 1e-9 of the kinetic energy above the previous
        // sample's (friction has removed more than that since).
        if (target && kind == Kind::contact && s.velocity_world.norm() > 1e-3) {
          const double kinetic = 0.5 * info.mass * s.velocity_world.squaredNorm();
          const double wanted = previous_energy + 1e-9 * kinetic - energy(s);
          s.velocity_world *= std::sqrt(1.0 + wanted / kinetic);
          summary.corrupted = true;
        }
        break;
      case Corruption::pushed_into_board:
        if (target && kind == Kind::contact) {
          s.position_world.z() -= 1e-6;
          summary.corrupted = true;
        }
        break;
      case Corruption::rest_ulp:
        if (target && kind == Kind::rest) {
          s.position_world.x() =
              std::nextafter(s.position_world.x(), std::numeric_limits<double>::infinity());
          summary.corrupted = true;
        }
        break;
      case Corruption::flight_rotation:
        if (target && kind == Kind::flight && n > 0) {
          s.orientation =
              Eigen::Quaterniond(Eigen::AngleAxisd(1e-6, Eigen::Vector3d::UnitZ())) * s.orientation;
          summary.corrupted = true;
        }
        break;
    }
    ++in_segment;
    previous_energy = energy(world.state(0));

    const ros::Time when = stamp(spec.start_ns + n * spec.dt_ns);
    nav_msgs::Odometry odom;
    odom.header.stamp = when;
    odom.header.frame_id = "world";
    odom.child_frame_id = "stone";
    odom.pose.pose = pose_msg(s);
    const Eigen::Quaterniond to_body = s.orientation.conjugate();
    odom.twist.twist.linear = vec_msg(to_body * s.velocity_world);
    odom.twist.twist.angular =
        vec_msg(to_body * model.angular_velocity_world(s.orientation, s.angular_momentum_world));
    const tf2_msgs::TFMessage tf =
        stone_tf_msg(odom.header, s.position_world, odom.pose.pose.orientation);
    bag.write("/stone/odom", when, odom);
    bag.write("/tf", when, tf);
    ++summary.odom;
  }
  bag.close();
  return summary;
}

}  // namespace virtual_go_test
