#include "virtual_go/go/stone_color.h"

#include "virtual_go/common/name_table.h"

namespace virtual_go {

namespace {

struct ColorEntry {
  std::string name;
  StoneColor color;
};

// The one place the colour names are written.
const NameTable<ColorEntry>& colors() {
  static const NameTable<ColorEntry> table(
      "stone color", "color", {{"black", StoneColor::black}, {"white", StoneColor::white}});
  return table;
}

}  // namespace

const std::string& stone_color_name(StoneColor color) {
  for (const ColorEntry& e : colors().entries()) {
    if (e.color == color) return e.name;
  }
  throw InvalidArgument(
      "color", "color: not a stone colour (" + std::to_string(static_cast<int>(color)) + ")");
}

StoneColor parse_stone_color(const std::string& name) { return colors().at(name).color; }

std::vector<std::string> stone_color_names() { return colors().names(); }

}  // namespace virtual_go
