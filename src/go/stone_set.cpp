#include "virtual_go/go/stone_set.h"

#include "virtual_go/common/validation.h"

namespace virtual_go {

StoneSpec set_stone_spec(StoneColor color) {
  StoneSpec spec;
  if (color == StoneColor::black) {
    spec.width = kBlackStoneWidth;
    spec.material = "slate";
  } else {
    spec.width = kWhiteStoneWidth;
    spec.material = "shell";
  }
  return spec;
}

StoneBody make_stone_body(StoneColor color, const StoneSpec& spec) {
  try {
    const Stone stone = make_stone(spec);
    return StoneBody{color, stone, LensGeometry(stone.shape)};
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(stone_color_name(color) + "/" + e.field(), e.what());
  }
}

StoneBody make_stone_body(const StoneSet& set, StoneColor color) {
  return make_stone_body(color, set.spec(color));
}

}  // namespace virtual_go
