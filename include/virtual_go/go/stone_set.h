// The stones of a real Go set, one body per colour (docs/physics.md, "Go stones"): black slate
// 22.2 mm wide, white shell 21.9 mm (white is made smaller so that both look the same size), both
// of size 33 (9.2 mm) unless set otherwise. Every stone in a world refers to the body of its
// colour, so black and white may differ in shape, mass and material.
#pragma once

#include "virtual_go/geometry/lens_geometry.h"
#include "virtual_go/go/stone.h"
#include "virtual_go/go/stone_color.h"

namespace virtual_go {

constexpr double kBlackStoneWidth = 0.0222;  // m, Nihon Ki-in sets
constexpr double kWhiteStoneWidth = 0.0219;  // m

// The set's default spec for a colour: black slate 22.2 mm, white shell 21.9 mm, the default
// size number (kDefaultSizeNumber, 33) giving the thickness.
StoneSpec set_stone_spec(StoneColor color);

// The specs of a set's two colours; each may be changed before the bodies are made.
struct StoneSet {
  StoneSpec black = set_stone_spec(StoneColor::black);
  StoneSpec white = set_stone_spec(StoneColor::white);

  const StoneSpec& spec(StoneColor color) const {
    return color == StoneColor::black ? black : white;
  }
  StoneSpec& spec(StoneColor color) { return color == StoneColor::black ? black : white; }
};

// One colour's body: what make_stone makes of its spec, and its contact geometry.
struct StoneBody {
  StoneColor color;
  Stone stone;        // shape, mass properties, density
  LensGeometry lens;  // the shape's contact geometry (support, reach)
};

// Throws InvalidArgument as make_stone does, its field() prefixed by the colour ("black/width",
// "white/material", ...).
StoneBody make_stone_body(StoneColor color, const StoneSpec& spec);
StoneBody make_stone_body(const StoneSet& set, StoneColor color);

}  // namespace virtual_go
