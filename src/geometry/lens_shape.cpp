#include "virtual_go/geometry/lens_shape.h"

#include <cmath>
#include <map>

#include "virtual_go/common/validation.h"

namespace virtual_go {
namespace {

// Japanese size number -> thickness in mm (DESIGN.md).
const std::map<int, double>& size_table_mm() {
  static const std::map<int, double> table = {
      {22, 6.3}, {25, 7.0}, {28, 7.5},  {30, 8.0},  {31, 8.4},  {32, 8.8},  {33, 9.2},
      {34, 9.5}, {35, 9.8}, {36, 10.1}, {37, 10.4}, {38, 10.7}, {39, 11.0}, {40, 11.3}};
  return table;
}

// Approximate densities in kg/m^3 (DESIGN.md).
const std::map<std::string, double>& density_table() {
  static const std::map<std::string, double> table = {
      {"slate", 2700.0}, {"shell", 2700.0}, {"glass", 2500.0}, {"yunzi", 2600.0}};
  return table;
}

}  // namespace

StoneShape::StoneShape(double width, double height) : width_(width), height_(height) {
  require_positive("stone width", width);
  require_positive("stone height", height);
  if (!(height < width)) {
    throw InvalidArgument("stone height must be less than the width " + format_value(width) +
                          " m, got " + format_value(height) + " m");
  }
}

StoneShape StoneShape::from_size(int size_number, double width) {
  return StoneShape(width, thickness_for_size(size_number));
}

double StoneShape::thickness_for_size(int size_number) {
  const auto it = size_table_mm().find(size_number);
  if (it == size_table_mm().end()) {
    std::string known;
    for (const auto& entry : size_table_mm()) known += " " + std::to_string(entry.first);
    throw InvalidArgument("unknown stone size number " + std::to_string(size_number) +
                          " (known:" + known + ")");
  }
  return it->second * 1e-3;
}

std::vector<int> StoneShape::size_numbers() {
  std::vector<int> numbers;
  for (const auto& entry : size_table_mm()) numbers.push_back(entry.first);
  return numbers;
}

double StoneShape::sphere_radius() const {
  const double a = half_width(), c = half_height();
  return (a * a + c * c) / (2 * c);
}

double StoneShape::sphere_center_offset() const { return sphere_radius() - half_height(); }

double StoneShape::volume() const {
  const double a = half_width(), c = half_height();
  return M_PI * c * (3 * a * a + c * c) / 3;
}

bool StoneShape::contains(double x, double y, double z) const {
  const double r = sphere_radius(), d = sphere_center_offset();
  const double rho2 = x * x + y * y;
  // Inside both spheres: centred at -d (upper cap) and +d (lower cap).
  return rho2 + (z + d) * (z + d) <= r * r && rho2 + (z - d) * (z - d) <= r * r;
}

double material_density(const std::string& material) {
  const auto it = density_table().find(material);
  if (it == density_table().end()) {
    std::string known;
    for (const auto& entry : density_table()) known += " " + entry.first;
    throw InvalidArgument("unknown stone material '" + material + "' (known:" + known + ")");
  }
  return it->second;
}

std::vector<std::string> material_names() {
  std::vector<std::string> names;
  for (const auto& entry : density_table()) names.push_back(entry.first);
  return names;
}

}  // namespace virtual_go
