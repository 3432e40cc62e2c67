// The Go stone's shape: a biconvex lens (the intersection of two equal spheres).
#pragma once

#include <string>
#include <vector>

namespace virtual_go {

constexpr double kDefaultStoneWidth = 0.022;  // m

class StoneShape {
 public:
  // width = lens diameter, height = thickness, in metres; 0 < height < width.
  StoneShape(double width, double height);

  // Japanese size number (22, 25, 28, 30..40) -> thickness; width defaults to 22 mm.
  static StoneShape from_size(int size_number, double width = kDefaultStoneWidth);
  static double thickness_for_size(int size_number);
  static std::vector<int> size_numbers();

  double width() const { return width_; }
  double height() const { return height_; }
  double half_width() const { return width_ / 2; }    // a
  double half_height() const { return height_ / 2; }  // c
  double sphere_radius() const;                       // R = (a^2 + c^2) / 2c
  double sphere_center_offset() const;                // R - c: centres at -/+ this on body z
  double volume() const;                              // pi c (3a^2 + c^2) / 3

  // True when the body-frame point lies inside (or on) the lens.
  bool contains(double x, double y, double z) const;

 private:
  double width_;
  double height_;
};

// Material name (slate, shell, glass, yunzi) -> density in kg/m^3.
double material_density(const std::string& material);
std::vector<std::string> material_names();

}  // namespace virtual_go
