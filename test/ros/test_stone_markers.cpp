// The MarkerArray of every stone (ros/stone_markers.h), without a master: one marker per stone
// keyed by its name, the shape of its colour, DELETE for a name drawn before and gone now.
#include <gtest/gtest.h>

#include <stdexcept>

#include "virtual_go/ros/stone_markers.h"

namespace vg = virtual_go;

namespace {

visualization_msgs::Marker prototype(float grey, const std::string& mesh) {
  visualization_msgs::Marker m;
  m.type = visualization_msgs::Marker::MESH_RESOURCE;
  m.mesh_resource = mesh;
  m.scale.x = m.scale.y = m.scale.z = 1.0;
  m.color.r = m.color.g = m.color.b = grey;
  m.color.a = 1.0f;
  return m;
}

const std::map<std::string, visualization_msgs::Marker> kPrototypes{
    {"black", prototype(0.06f, "file:///black.stl")},
    {"white", prototype(0.93f, "file:///white.stl")}};

vg::StoneMarker stone(const std::string& name, const std::string& color) {
  vg::StoneMarker s{name, color, name, {}};
  s.pose.orientation.w = 1.0;
  return s;
}

}  // namespace

TEST(StoneMarkers, OneMarkerPerStoneKeyedByNameWithItsColoursShape) {
  vg::StoneMarker moved = stone("white_1", "white");
  moved.frame_id = "world";
  moved.pose.position.x = 0.022;
  const visualization_msgs::MarkerArray a =
      vg::to_stone_markers_msg({stone("black_1", "black"), moved}, {}, kPrototypes);
  ASSERT_EQ(a.markers.size(), 2u);
  EXPECT_EQ(a.markers[0].ns, "black_1");
  EXPECT_EQ(a.markers[0].id, 0);
  EXPECT_EQ(a.markers[0].action, visualization_msgs::Marker::ADD);
  EXPECT_EQ(a.markers[0].header.frame_id, "black_1");
  EXPECT_TRUE(a.markers[0].frame_locked);
  EXPECT_EQ(a.markers[0].header.stamp, ros::Time());
  EXPECT_EQ(a.markers[0].mesh_resource, "file:///black.stl");
  EXPECT_FLOAT_EQ(a.markers[0].color.r, 0.06f);
  EXPECT_EQ(a.markers[1].ns, "white_1");
  EXPECT_EQ(a.markers[1].mesh_resource, "file:///white.stl");
  EXPECT_EQ(a.markers[1].header.frame_id, "world");
  EXPECT_EQ(a.markers[1].pose.position.x, 0.022);
}

TEST(StoneMarkers, NamesDrawnBeforeAndGoneAreDeleted) {
  const visualization_msgs::MarkerArray a = vg::to_stone_markers_msg(
      {stone("black_2", "black")}, {"black_1", "black_2", "white_1"}, kPrototypes);
  ASSERT_EQ(a.markers.size(), 3u);
  EXPECT_EQ(a.markers[0].ns, "black_2");
  EXPECT_EQ(a.markers[0].action, visualization_msgs::Marker::ADD);
  EXPECT_EQ(a.markers[1].ns, "black_1");
  EXPECT_EQ(a.markers[1].id, 0);
  EXPECT_EQ(a.markers[1].action, visualization_msgs::Marker::DELETE);
  EXPECT_EQ(a.markers[2].ns, "white_1");
  EXPECT_EQ(a.markers[2].action, visualization_msgs::Marker::DELETE);
  // Nothing left: only deletions.
  const visualization_msgs::MarkerArray empty =
      vg::to_stone_markers_msg({}, {"black_2"}, kPrototypes);
  ASSERT_EQ(empty.markers.size(), 1u);
  EXPECT_EQ(empty.markers[0].action, visualization_msgs::Marker::DELETE);
}

TEST(StoneMarkers, AColourWithoutAShapeIsRefusedByName) {
  try {
    vg::to_stone_markers_msg({stone("red_1", "red")}, {}, kPrototypes);
    ADD_FAILURE() << "a stone without a prototype was drawn";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'red' (stone red_1)"), std::string::npos) << e.what();
  }
}
