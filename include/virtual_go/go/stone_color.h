// The two colours of Go stones, named as messages and services spell them ("black", "white").
#pragma once

#include <string>
#include <vector>

namespace virtual_go {

enum class StoneColor { black, white };

// "black" or "white".
const std::string& stone_color_name(StoneColor color);
// Exact lowercase names; anything else throws InvalidArgument (field "color") listing the names.
StoneColor parse_stone_color(const std::string& name);
// The names in table order: black, white.
std::vector<std::string> stone_color_names();
// The other colour.
constexpr StoneColor opponent(StoneColor color) {
  return color == StoneColor::black ? StoneColor::white : StoneColor::black;
}

}  // namespace virtual_go
