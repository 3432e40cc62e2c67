#include "virtual_go/go/stone_materials.h"

namespace virtual_go {

const NameTable<StoneMaterial>& stone_materials() {
  // Approximate densities (docs/physics.md, "Go stones").
  static const NameTable<StoneMaterial> table(
      "stone material", "stone material",
      {{"glass", 2500.0}, {"shell", 2700.0}, {"slate", 2700.0}, {"yunzi", 2600.0}});
  return table;
}

double material_density(const std::string& material) {
  return stone_materials().at(material).density;
}

std::vector<std::string> material_names() { return stone_materials().names(); }

}  // namespace virtual_go
