#include "virtual_go/go/stone.h"

#include "virtual_go/common/validation.h"

namespace virtual_go {
namespace {

// Runs one stage of make_stone and blames any InvalidArgument on the StoneSpec member `field`
// (the message, which names the value, stays as it is).
template <class Stage>
auto blaming(const char* field, Stage&& stage) {
  try {
    return stage();
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(field, e.what());
  }
}

}  // namespace

Stone make_stone(const StoneSpec& spec) {
  blaming("width", [&] { require_positive("stone width", spec.width); });
  // Checked even when density or mass override it: a misspelt material is still an error.
  const double material_rho = blaming("material", [&] { return material_density(spec.material); });
  if (spec.density) blaming("density", [&] { require_positive("density", *spec.density); });
  const double size_height = blaming("size_number", [&] {
    return thickness_for_size(spec.size_number.value_or(kDefaultSizeNumber));
  });
  // Without a given height or size, the height is the default size's: a width not above it
  // is the width's fault (the user set only the width), not the size's.
  if (!spec.height && !spec.size_number && !(size_height < spec.width)) {
    throw InvalidArgument("width", "stone width " + format_value(spec.width) +
                                       " m must be more than the height " +
                                       format_value(size_height) + " m of the default size " +
                                       std::to_string(kDefaultSizeNumber));
  }
  // The width is fine by now: what the lens refuses is the height, from whichever field set it.
  const char* height_field = spec.height ? "height" : "size_number";
  const LensShape shape = blaming(
      height_field, [&] { return LensShape(spec.width, spec.height.value_or(size_height)); });
  // A mass or inertia that underflows comes from the override that set it, else the dimensions.
  const char* mass_field = spec.mass      ? "mass"
                           : spec.density ? "density"
                           : spec.height  ? "height"
                                          : "width";
  return blaming(mass_field, [&] {
    if (spec.mass) {
      return Stone{shape, MassProperties::of_lens_with_mass(shape, *spec.mass),
                   *spec.mass / shape.volume()};
    }
    const double density = spec.density ? *spec.density : material_rho;
    return Stone{shape, MassProperties::of_lens(shape, density), density};
  });
}

}  // namespace virtual_go
