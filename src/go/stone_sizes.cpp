#include "virtual_go/go/stone_sizes.h"

#include <map>
#include <string>

#include "virtual_go/common/validation.h"

namespace virtual_go {
namespace {

// Japanese size number -> thickness in mm (docs/physics.md, "Go stones").
const std::map<int, double>& size_table_mm() {
  static const std::map<int, double> table = {
      {22, 6.3}, {25, 7.0}, {28, 7.5},  {30, 8.0},  {31, 8.4},  {32, 8.8},  {33, 9.2},
      {34, 9.5}, {35, 9.8}, {36, 10.1}, {37, 10.4}, {38, 10.7}, {39, 11.0}, {40, 11.3}};
  return table;
}

}  // namespace

double thickness_for_size(int size_number) {
  const auto it = size_table_mm().find(size_number);
  if (it == size_table_mm().end()) {
    std::string known;
    for (const int n : size_numbers()) known += " " + std::to_string(n);
    throw InvalidArgument(
        "stone size number",
        "unknown stone size number " + std::to_string(size_number) + " (known:" + known + ")");
  }
  return it->second * 1e-3;
}

std::vector<int> size_numbers() {
  std::vector<int> numbers;
  for (const auto& entry : size_table_mm()) numbers.push_back(entry.first);
  return numbers;
}

LensShape lens_for_size(int size_number, double width) {
  return LensShape(width, thickness_for_size(size_number));
}

}  // namespace virtual_go
