// Go stone materials and their densities (docs/physics.md, "Go stones").
#pragma once

#include <string>
#include <vector>

#include "virtual_go/common/name_table.h"

namespace virtual_go {

struct StoneMaterial {
  std::string name;
  double density;  // kg/m^3, approximate
};

// glass, shell, slate, yunzi (alphabetical); an unknown name is an InvalidArgument (field "stone
// material").
const NameTable<StoneMaterial>& stone_materials();
// The density (kg/m^3) of a material by name.
double material_density(const std::string& material);
std::vector<std::string> material_names();

}  // namespace virtual_go
