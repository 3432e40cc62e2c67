// ~place, ~remove and ~clear with a real master (test/ros/config/stones_drop.yaml: the initial
// stone, white_stone, rests on D16). Stones set down at Go points read back from ~stones with
// their names, colours and points, lying on the board's top face at the intersection's x and y
// (the board's pitch, 22 mm across and 23.7 mm along, from the config's board size); their tf
// frames found by a tf2 listener, also once they rest; removal by name and by point; clear (the
// initial stone too, back with ~reset); ~set_state and ~set_angular_velocity by name.
#include <gtest/gtest.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/transform_listener.h>

#include <optional>
#include <string>

#include "support/node_observer.h"
#include "virtual_go/PlaceStone.h"
#include "virtual_go/RemoveStone.h"
#include "virtual_go/SetAngularVelocity.h"
#include "virtual_go/SetState.h"
#include "virtual_go/StoneStates.h"

using vgtest::NodeObserver;

namespace {

std::optional<std::size_t> index_of(const virtual_go::StoneStates& s, const std::string& name) {
  for (std::size_t i = 0; i < s.name.size(); ++i) {
    if (s.name[i] == name) return i;
  }
  return std::nullopt;
}

}  // namespace

TEST(StoneNodePlace, PlaceRemoveAndClearShowOnStonesAndTf) {
  NodeObserver o;
  ros::NodeHandle nh;
  std::optional<virtual_go::StoneStates> stones;
  ros::Subscriber sub = nh.subscribe<virtual_go::StoneStates>(
      "/stone/stones", 10, [&](const virtual_go::StoneStates::ConstPtr& m) { stones = *m; });
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  ASSERT_TRUE(o.wait_for_start());

  virtual_go::PlaceStone black;
  black.request.point = "D4";
  black.request.color = "black";
  ASSERT_TRUE(o.call("place", black));
  ASSERT_TRUE(black.response.success) << black.response.message;
  EXPECT_EQ(black.response.name, "black_1");
  virtual_go::PlaceStone white;
  white.request.point = "Q16";
  white.request.color = "white";
  white.request.drop_height = 0.02;
  ASSERT_TRUE(o.call("place", white));
  ASSERT_TRUE(white.response.success) << white.response.message;
  EXPECT_EQ(white.response.name, "white_1");
  virtual_go::PlaceStone bad;
  bad.request.point = "I3";  // columns skip I
  bad.request.color = "black";
  ASSERT_TRUE(o.call("place", bad));
  EXPECT_FALSE(bad.response.success);
  EXPECT_NE(bad.response.message.find("point"), std::string::npos) << bad.response.message;

  // Both on ~stones, resting at their points (the dropped one after its bounces).
  const auto both_rest = [&] {
    if (!stones) return false;
    const auto b = index_of(*stones, "black_1");
    const auto w = index_of(*stones, "white_1");
    return b && w && stones->resting[*b] && stones->resting[*w];
  };
  ASSERT_TRUE(o.wait_until(both_rest, 20.0));
  const std::size_t b = *index_of(*stones, "black_1");
  const std::size_t w = *index_of(*stones, "white_1");
  EXPECT_EQ(stones->point[b], "D4");
  EXPECT_EQ(stones->color[b], "black");
  EXPECT_EQ(stones->point[w], "Q16");
  EXPECT_EQ(stones->color[w], "white");
  // D4: 6 lines left of and 6 below tengen (the origin): x = -6 * 22 mm, y = -6 * 23.7 mm; its
  // lowest point on the top face, which the initial stone at rest shows (z = half its height).
  EXPECT_NEAR(stones->pose[b].position.x, -6 * 0.022, 1e-9);
  EXPECT_NEAR(stones->pose[b].position.y, -6 * 0.0237, 1e-9);
  const std::size_t s0 = *index_of(*stones, "white_stone");
  const double top_z = stones->pose[s0].position.z - 0.5 * stones->height[s0];
  EXPECT_NEAR(stones->pose[b].position.z - 0.5 * stones->height[b], top_z, 1e-9);

  // tf: both frames, at rest too (re-sent once a second of simulated time).
  ros::Duration(1.5).sleep();
  ASSERT_TRUE(o.wait_until([&] { return buffer.canTransform("world", "black_1", ros::Time(0)); }));
  const geometry_msgs::TransformStamped tf_b =
      buffer.lookupTransform("world", "black_1", ros::Time(0));
  EXPECT_NEAR(tf_b.transform.translation.x, stones->pose[b].position.x, 1e-15);
  EXPECT_NEAR(tf_b.transform.translation.y, stones->pose[b].position.y, 1e-15);
  EXPECT_GT(tf_b.header.stamp, stones->header.stamp);  // re-sent while resting
  EXPECT_TRUE(buffer.canTransform("world", "white_1", ros::Time(0)));

  // Remove by point and by name, then clear.
  virtual_go::RemoveStone by_point;
  by_point.request.name = "q16";
  ASSERT_TRUE(o.call("remove", by_point));
  ASSERT_TRUE(by_point.response.success) << by_point.response.message;
  EXPECT_EQ(by_point.response.message.rfind("white_1", 0), 0u) << by_point.response.message;
  ASSERT_TRUE(o.wait_until([&] { return !index_of(*stones, "white_1"); }, 10.0));
  EXPECT_TRUE(index_of(*stones, "black_1"));
  virtual_go::PlaceStone again;
  again.request.point = "K10";
  again.request.color = "white";
  ASSERT_TRUE(o.call("place", again));
  EXPECT_EQ(again.response.name, "white_2");  // never reused
  std_srvs::Trigger clear;
  ASSERT_TRUE(o.call("clear", clear));
  ASSERT_TRUE(clear.response.success) << clear.response.message;
  // Every stone goes, the initial one too (a game replayed onto the board has no other stone).
  ASSERT_TRUE(o.wait_until([&] { return stones->name.empty(); }, 10.0));
  std::size_t placed = 0, removed = 0, cleared = 0;
  for (const virtual_go::StoneEvent& e : o.events) {
    placed += e.reason == "place";
    removed += e.reason == "remove";
    cleared += e.reason == "clear";
  }
  EXPECT_EQ(placed, 3u);
  EXPECT_EQ(removed, 1u);
  EXPECT_EQ(cleared, 3u);
  virtual_go::RemoveStone gone;
  gone.request.name = "black_1";
  ASSERT_TRUE(o.call("remove", gone));
  EXPECT_FALSE(gone.response.success);
  // The removed initial stone: requests for it say so; ~reset puts it back.
  virtual_go::SetState teleport;
  teleport.request.pose.orientation.w = 1.0;
  teleport.request.pose.position.z = 0.1;
  ASSERT_TRUE(o.call("set_state", teleport));
  EXPECT_FALSE(teleport.response.success);
  EXPECT_NE(teleport.response.message.find("'white_stone' is removed"), std::string::npos)
      << teleport.response.message;
  std_srvs::Trigger reset;
  ASSERT_TRUE(o.call("reset", reset));
  ASSERT_TRUE(reset.response.success) << reset.response.message;
  ASSERT_TRUE(o.wait_until(
      [&] { return stones->name.size() == 1 && stones->name[0] == "white_stone"; }, 10.0));
}

// ~set_state and ~set_angular_velocity of a placed stone by its name; an unknown name refused
// naming it and the stones there are.
TEST(StoneNodePlace, NamedRequestsMoveThatStone) {
  NodeObserver o;
  ros::NodeHandle nh;
  std::optional<virtual_go::StoneStates> stones;
  ros::Subscriber sub = nh.subscribe<virtual_go::StoneStates>(
      "/stone/stones", 10, [&](const virtual_go::StoneStates::ConstPtr& m) { stones = *m; });
  virtual_go::PlaceStone c3;
  c3.request.point = "C3";
  c3.request.color = "black";
  ASSERT_TRUE(o.call("place", c3));
  ASSERT_TRUE(c3.response.success) << c3.response.message;
  const std::string name = c3.response.name;
  ASSERT_TRUE(o.wait_until([&] {
    const auto k = stones ? index_of(*stones, name) : std::nullopt;
    return k && stones->resting[*k];
  }));
  const geometry_msgs::Pose rest = stones->pose[*index_of(*stones, name)];

  virtual_go::SetState lift;
  lift.request.name = name;
  lift.request.pose = rest;
  lift.request.pose.position.z += 0.02;
  ASSERT_TRUE(o.call("set_state", lift));
  ASSERT_TRUE(lift.response.success) << lift.response.message;
  const auto named = [&](const std::string& reason) -> const virtual_go::StoneEvent* {
    for (const virtual_go::StoneEvent& e : o.events) {
      if (e.stone == name && e.reason == reason) return &e;
    }
    return nullptr;
  };
  ASSERT_TRUE(o.wait_until([&] { return named("set_state") && named("impact"); }));
  EXPECT_EQ(named("set_state")->pose.position.z, rest.position.z + 0.02);
  EXPECT_EQ(named("set_state")->pose.position.x, rest.position.x);

  virtual_go::SetAngularVelocity spin;
  spin.request.name = name;
  spin.request.angular_velocity.z = 3.0;
  ASSERT_TRUE(o.call("set_angular_velocity", spin));
  ASSERT_TRUE(spin.response.success) << spin.response.message;
  ASSERT_TRUE(o.wait_until([&] { return named("set_angular_velocity") != nullptr; }));

  virtual_go::SetState unknown = lift;
  unknown.request.name = "black_99";
  ASSERT_TRUE(o.call("set_state", unknown));
  EXPECT_FALSE(unknown.response.success);
  EXPECT_NE(unknown.response.message.find("'black_99' is no stone"), std::string::npos)
      << unknown.response.message;
  EXPECT_NE(unknown.response.message.find("white_stone, " + name), std::string::npos)
      << unknown.response.message;
}
