// A Go stone as configured by a user: size, material, optional overrides -> shape and mass.
#pragma once

#include <optional>
#include <string>

#include "virtual_go/body/mass_properties.h"
#include "virtual_go/geometry/lens_shape.h"
#include "virtual_go/go/stone_materials.h"
#include "virtual_go/go/stone_sizes.h"

namespace virtual_go {

struct StoneSpec {
  std::optional<int> size_number;  // Japanese size number; sets the height unless height is given
  double width = kDefaultStoneWidth;  // m
  std::optional<double> height;       // m; overrides size_number
  std::string material = "slate";
  std::optional<double> density;  // kg/m^3; overrides material
  std::optional<double> mass;     // kg; overrides density and material
};

struct Stone {
  LensShape shape;
  MassProperties mass_properties;
  double density;  // kg/m^3, the effective uniform density
};

// Default height when neither size nor height is given: size kDefaultSizeNumber. Checks every
// given field, also one that a later override makes unused. Throws InvalidArgument whose
// field() is the StoneSpec member to blame: "size_number", "width", "height", "material",
// "density" or "mass" (a derived mass or inertia that underflows blames the override that set
// it, else the dimensions).
Stone make_stone(const StoneSpec& spec);

}  // namespace virtual_go
