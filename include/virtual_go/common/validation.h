// Input checks shared by the core: every rejection names its field and the offending value.
#pragma once

#include <Eigen/Geometry>
#include <stdexcept>
#include <string>
#include <string_view>

#include "virtual_go/common/formatting.h"

namespace virtual_go {

// Thrown for bad input. field() names the input that was wrong as the throwing function's caller
// knows it ("dt", "orientation", "width"), so a caller can map it to its own names (a ROS
// parameter, a service field) without reading the message; what() is the sentence for people,
// naming the field and the value.
class InvalidArgument : public std::invalid_argument {
 public:
  InvalidArgument(std::string field, const std::string& message)
      : std::invalid_argument(message), field_(std::move(field)) {}
  const std::string& field() const noexcept { return field_; }

 private:
  std::string field_;
};

// Thrown when an integrator cannot keep up (for instance h * |omega| too large for euler or rk4)
// or a step would produce a non-finite state. The state passed in is left unchanged.
class IntegrationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Each throws InvalidArgument with `field` as field() and at the start of the message. The
// field is a view: these checks run on every validated state, and a std::string parameter would
// build (and for names past 15 characters allocate) a string on every call, not only on failure.
void require_finite(std::string_view field, double value);
void require_finite(std::string_view field, const Eigen::Vector3d& v);
void require_positive(std::string_view field, double value);

// |v| for any finite v, without the overflow (or underflow) of the plain sum of squares: a
// component above 1.3e154 makes v.norm() infinite. Infinite only when |v| itself exceeds the
// largest double. For checking inputs against limits; cheaper norms serve bounded values.
double norm_without_overflow(const Eigen::Vector3d& v);
// "= 2e+200" as messages print a norm after "|v| ", or "> 1.7976931348623157e+308" when |v|
// exceeds the largest double.
std::string norm_text(const Eigen::Vector3d& v);

// Returns q / |q|; throws for a non-finite or (near) zero quaternion.
Eigen::Quaterniond require_unit_quaternion(std::string_view field, const Eigen::Quaterniond& q);

}  // namespace virtual_go
