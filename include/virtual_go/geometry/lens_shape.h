// A biconvex lens: the intersection of two equal spheres, the shape of a Go stone. Body frame:
// origin at the centre, z along the symmetry axis (docs/physics.md, "The lens").
#pragma once

namespace virtual_go {

class LensShape {
 public:
  // width = lens diameter, height = thickness, in metres; 0 < height < width. Throws
  // InvalidArgument with field "stone width" or "stone height".
  LensShape(double width, double height);

  double width() const { return width_; }
  double height() const { return height_; }
  double half_width() const { return width_ / 2; }    // a
  double half_height() const { return height_ / 2; }  // c
  double sphere_radius() const;                       // R = (a^2 + c^2) / 2c
  double sphere_center_offset() const;                // R - c: centres at -/+ this on body z
  double volume() const;                              // pi c (3a^2 + c^2) / 3, m^3

  // True when the body-frame point (m) lies inside (or on) the lens.
  bool contains(double x, double y, double z) const;

 private:
  double width_;
  double height_;
};

}  // namespace virtual_go
