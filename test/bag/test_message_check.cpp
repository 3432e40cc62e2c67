// Declared sizes against bytes before deserialising (bag/message_check.h): a message's own
// lengths can never make the reader allocate for elements that are not there.
#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <tf2_msgs/TFMessage.h>

#include <cstring>
#include <vector>

#include "virtual_go/bag/message_check.h"

namespace vb = virtual_go::bag;

namespace {

template <class M>
std::vector<std::uint8_t> serialize(const M& message) {
  std::vector<std::uint8_t> bytes(ros::serialization::serializationLength(message));
  ros::serialization::OStream out(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  ros::serialization::serialize(out, message);
  return bytes;
}

tf2_msgs::TFMessage one_transform() {
  tf2_msgs::TFMessage tf;
  geometry_msgs::TransformStamped t;
  t.header.frame_id = "world";
  t.child_frame_id = "stone";
  t.transform.translation.z = 0.05;
  t.transform.rotation.w = 1.0;
  tf.transforms.push_back(t);
  return tf;
}

}  // namespace

TEST(MessageCheck, IntactMessagesPassAndReadBack) {
  const tf2_msgs::TFMessage tf = one_transform();
  const std::vector<std::uint8_t> bytes = serialize(tf);
  EXPECT_EQ(bytes.size(), 90u);  // the size of the /tf message of issue 8
  const tf2_msgs::TFMessage back = vb::checked_deserialize<tf2_msgs::TFMessage>(bytes);
  ASSERT_EQ(back.transforms.size(), 1u);
  EXPECT_EQ(back.transforms[0].child_frame_id, "stone");
  EXPECT_EQ(back.transforms[0].transform.translation.z, 0.05);
  nav_msgs::Odometry odom;  // fixed-size arrays (covariance) and nested messages
  odom.header.frame_id = "world";
  odom.twist.covariance[35] = 2.5;
  EXPECT_EQ(vb::checked_deserialize<nav_msgs::Odometry>(serialize(odom)).twist.covariance[35], 2.5);
}

TEST(MessageCheck, CorruptArrayLengthIsRefusedBeforeAnyAllocation) {
  std::vector<std::uint8_t> bytes = serialize(one_transform());
  const std::uint32_t declared = 30000000;  // 4 GB of TransformStamped, as in issue 8
  std::memcpy(bytes.data(), &declared, 4);
  try {
    vb::checked_deserialize<tf2_msgs::TFMessage>(bytes);
    ADD_FAILURE() << "accepted";
  } catch (const vb::CorruptMessage& e) {
    EXPECT_STREQ(e.what(),
                 "an array declares 30000000 elements of at least 76 bytes each, only 86 bytes "
                 "remain");
  }
  // Two elements need more than the one that is there: refused as well, after walking the first.
  const std::uint32_t two = 2;
  std::memcpy(bytes.data(), &two, 4);
  EXPECT_THROW(vb::checked_deserialize<tf2_msgs::TFMessage>(bytes), vb::CorruptMessage);
}

TEST(MessageCheck, CorruptStringLengthAndTruncationAreRefused) {
  std::vector<std::uint8_t> bytes = serialize(one_transform());
  const std::uint32_t huge = 0xfffffff0u;  // frame_id's length, after count, seq and stamp
  std::vector<std::uint8_t> corrupt = bytes;
  std::memcpy(corrupt.data() + 16, &huge, 4);
  EXPECT_THROW(vb::checked_deserialize<tf2_msgs::TFMessage>(corrupt), vb::CorruptMessage);
  for (std::size_t size : {0u, 3u, 20u, 89u}) {
    const std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + size);
    EXPECT_THROW(vb::checked_deserialize<tf2_msgs::TFMessage>(cut), vb::CorruptMessage) << size;
  }
}
