#include "virtual_go/go/stone.h"

#include "virtual_go/common/validation.h"

namespace virtual_go {

Stone make_stone(const StoneSpec& spec) {
  require_positive("stone width", spec.width);
  // Checked even when density or mass override it: a misspelt material is still an error.
  const double material_rho = material_density(spec.material);
  // Every given field is checked, also one that a later override makes unused.
  if (spec.density) require_positive("density", *spec.density);
  double height = StoneShape::thickness_for_size(spec.size_number.value_or(33));
  if (spec.height) height = *spec.height;
  const StoneShape shape(spec.width, height);
  if (spec.mass) {
    const MassProperties mass = MassProperties::of_lens_with_mass(shape, *spec.mass);
    return Stone{shape, mass, *spec.mass / shape.volume()};
  }
  const double density = spec.density ? *spec.density : material_rho;
  return Stone{shape, MassProperties::of_lens(shape, density), density};
}

}  // namespace virtual_go
