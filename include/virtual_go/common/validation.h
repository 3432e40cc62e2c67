// Input checks shared by the core: every rejection names the field and the value.
#pragma once

#include <Eigen/Geometry>
#include <stdexcept>
#include <string>

namespace virtual_go {

// Thrown for bad input; what() names the field and the offending value.
class InvalidArgument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Thrown when an integrator cannot keep up (for instance h * |omega| too large for euler or rk4)
// or a step would produce a non-finite state. The state passed in is left unchanged.
class IntegrationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::string format_value(double value);
std::string format_vector(const Eigen::Vector3d& v);

void require_finite(const std::string& field, double value);
void require_finite(const std::string& field, const Eigen::Vector3d& v);
void require_positive(const std::string& field, double value);

// Returns q / |q|; throws for a non-finite or (near) zero quaternion.
Eigen::Quaterniond require_unit_quaternion(const std::string& field, const Eigen::Quaterniond& q);

}  // namespace virtual_go
