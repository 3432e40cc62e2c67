// Go stone sizes: the Japanese size number sets the thickness (docs/physics.md, "Go stones").
#pragma once

#include <vector>

#include "virtual_go/geometry/lens_shape.h"

namespace virtual_go {

constexpr double kDefaultStoneWidth = 0.022;  // m
constexpr int kDefaultSizeNumber = 33;        // 9.2 mm thick

// Size number (22, 25, 28, 30..40) -> thickness in m; InvalidArgument (field "stone size
// number") for any other number.
double thickness_for_size(int size_number);
// The known size numbers, ascending.
std::vector<int> size_numbers();
// The lens of that size number and width (m).
LensShape lens_for_size(int size_number, double width = kDefaultStoneWidth);

}  // namespace virtual_go
