// Checks a serialized ROS message's declared sizes against its bytes before it is deserialised.
// roscpp's deserialiser resizes a vector to the length the bytes declare before it reads the
// elements, so one corrupt length (a 90-byte tf2_msgs/TFMessage declaring 30 million
// transforms) makes it allocate gigabytes before the read runs out of bytes. This walks the
// bytes field by field as the deserialiser would (through the generated allInOne, so the
// layout is the compiled type's, not a text the bag carries) and refuses any array or string
// whose declared length cannot fit in the bytes that remain. It allocates one element per
// nesting level, whatever the lengths say.
#pragma once

#include <ros/message_traits.h>
#include <ros/serialization.h>
#include <ros/time.h>

#include <boost/array.hpp>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace virtual_go {
namespace bag {

// A message whose bytes contradict its declared sizes; what() says which size and by how much.
class CorruptMessage : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class SizeCheckStream {
 public:
  SizeCheckStream(const std::uint8_t* data, std::uint32_t size) : data_(data), left_(size) {}

  // What the generated Serializer<M>::allInOne calls for each field.
  template <class T>
  void next(T& value) {
    walk(value);
  }
  std::uint32_t left() const { return left_; }

 private:
  void take(std::uint64_t bytes, const char* what) {
    if (bytes > left_) {
      throw CorruptMessage(std::string(what) + " needs " + std::to_string(bytes) + " bytes, only " +
                           std::to_string(left_) + " remain");
    }
    data_ += bytes;
    left_ -= static_cast<std::uint32_t>(bytes);
  }

  std::uint32_t length(const char* what) {
    if (left_ < 4) take(4, what);
    std::uint32_t n = 0;
    std::memcpy(&n, data_, 4);  // little-endian, as ROS serializes on the hosts it runs on
    data_ += 4;
    left_ -= 4;
    return n;
  }

  template <class T>
  std::enable_if_t<std::is_arithmetic<T>::value> walk(T&) {
    take(sizeof(T), "a number");
  }
  void walk(ros::Time&) { take(8, "a time"); }
  void walk(ros::Duration&) { take(8, "a duration"); }
  template <class C, class Traits, class A>
  void walk(std::basic_string<C, Traits, A>&) {
    const std::uint32_t n = length("a string's length");
    take(n, ("a string of " + std::to_string(n) + " bytes").c_str());
  }
  template <class T, std::size_t N>
  void walk(boost::array<T, N>& elements) {
    for (T& e : elements) walk(e);
  }
  template <class T, class A>
  void walk(std::vector<T, A>&) {
    const std::uint32_t n = length("an array's length");
    if (n == 0) return;
    // The least an element can take: its fixed part, with every array and string inside it
    // empty (a default element serialises to exactly that).
    T element{};
    const std::uint64_t least = ros::serialization::serializationLength(element);
    if (least * n > left_) {
      throw CorruptMessage("an array declares " + std::to_string(n) + " elements of at least " +
                           std::to_string(least) + " bytes each, only " + std::to_string(left_) +
                           " bytes remain");
    }
    if (least == 0) return;  // elements of no bytes: nothing to walk
    for (std::uint32_t i = 0; i < n; ++i) walk(element);
  }
  template <class M>
  std::enable_if_t<ros::message_traits::IsMessage<M>::value> walk(M& message) {
    ros::serialization::Serializer<M>::template allInOne<SizeCheckStream, M&>(*this, message);
  }

  const std::uint8_t* data_;
  std::uint32_t left_;
};

// Throws CorruptMessage when `bytes` cannot hold a message of type M as its sizes declare.
template <class M>
void check_sizes(const std::uint8_t* bytes, std::uint32_t size) {
  M scratch;
  SizeCheckStream stream(bytes, size);
  stream.next(scratch);
}

// Deserialises a message of type M from `bytes` after check_sizes.
template <class M>
M checked_deserialize(const std::vector<std::uint8_t>& bytes) {
  const auto size = static_cast<std::uint32_t>(bytes.size());
  check_sizes<M>(bytes.data(), size);
  M message;
  ros::serialization::IStream in(const_cast<std::uint8_t*>(bytes.data()), size);
  ros::serialization::deserialize(in, message);
  return message;
}

}  // namespace bag
}  // namespace virtual_go
