// Mass properties of the biconvex lens: the closed forms against an independent numeric
// integration (two ways: disc slices along z and cylindrical shells), the sphere and thin-disc
// limits, and the worked example in docs/physics.md ("The lens").
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "virtual_go/body/mass_properties.h"
#include "virtual_go/geometry/lens_shape.h"
#include "virtual_go/go/stone.h"

namespace vg = virtual_go;

namespace {

// Composite Simpson on [lo, hi] with n (even) intervals.
double simpson(const std::function<double(double)>& f, double lo, double hi, int n) {
  const double h = (hi - lo) / n;
  double sum = f(lo) + f(hi);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(lo + i * h);
  return sum * h / 3.0;
}

struct Integrated {
  double volume, i3_per_density, i1_per_density;
};

// Geometry rederived here: the upper face is a sphere through the rim (a, 0) and the pole
// (0, c) centred on the axis at -d, so a^2 + d^2 = (c + d)^2, d = (a^2 - c^2) / 2c.
double centre_offset(double a, double c) { return (a * a - c * c) / (2 * c); }

// Slices perpendicular to z: a disc of radius^2 r2(z) = (c + d)^2 - (z + d)^2 for z in [0, c],
// mirrored below. Disc about its axis: pi r^4 / 2 per unit thickness; about a diameter
// pi r^4 / 4, plus pi r^2 z^2 by the parallel-axis theorem.
Integrated integrate_slices(double a, double c) {
  const double d = centre_offset(a, c);
  auto r2 = [&](double z) { return (c + d) * (c + d) - (z + d) * (z + d); };
  const int n = 4000;
  Integrated out;
  out.volume = 2 * simpson([&](double z) { return M_PI * r2(z); }, 0, c, n);
  out.i3_per_density = 2 * simpson([&](double z) { return M_PI * r2(z) * r2(z) / 2; }, 0, c, n);
  out.i1_per_density =
      2 *
      simpson([&](double z) { return M_PI * r2(z) * r2(z) / 4 + M_PI * r2(z) * z * z; }, 0, c, n);
  return out;
}

// Cylindrical shells of radius r in [0, a], half-thickness t(r) = sqrt(R^2 - r^2) - d:
// mass 2 pi r 2t dr; about z r^2; about x the mean of x^2 over the ring (r^2 / 2) plus the mean
// of z^2 over [-t, t] (t^2 / 3). Substituting r = R sin(alpha) keeps the integrand smooth even
// for a near-sphere, where sqrt(R^2 - r^2) is steep at the rim.
Integrated integrate_shells(double a, double c) {
  const double d = centre_offset(a, c), big_r = c + d;
  const double alpha_rim = std::asin(a / big_r);
  // Integral over the shells of (2 pi r) (2 t) f(r, t) dr, with dr = R cos(alpha) d(alpha).
  auto over_shells = [&](const std::function<double(double, double)>& f) {
    return simpson(
        [&](double alpha) {
          const double r = big_r * std::sin(alpha), t = big_r * std::cos(alpha) - d;
          return 2 * M_PI * r * 2 * t * f(r, t) * big_r * std::cos(alpha);
        },
        0, alpha_rim, 4000);
  };
  Integrated out;
  out.volume = over_shells([](double, double) { return 1.0; });
  out.i3_per_density = over_shells([](double r, double) { return r * r; });
  out.i1_per_density = over_shells([](double r, double t) { return r * r / 2 + t * t / 3; });
  return out;
}

void expect_relative(double expected, double actual, double tolerance, const char* what) {
  EXPECT_NEAR(actual / expected, 1.0, tolerance)
      << what << ": expected " << expected << ", got " << actual;
}

}  // namespace

TEST(MassProperties, ClosedFormMatchesSliceAndShellIntegration) {
  const double density = 2600.0;
  // Every catalogue size, plus a nearly flat and a nearly round lens.
  std::vector<std::pair<double, double>> shapes;
  for (int size : vg::size_numbers()) {
    shapes.emplace_back(0.022, vg::thickness_for_size(size));
  }
  shapes.emplace_back(0.030, 0.001);
  shapes.emplace_back(0.020, 0.0195);
  for (const auto& [w, h] : shapes) {
    SCOPED_TRACE("width " + std::to_string(w) + " height " + std::to_string(h));
    const vg::LensShape shape(w, h);
    const vg::MassProperties mp = vg::MassProperties::of_lens(shape, density);
    for (const Integrated& num : {integrate_slices(w / 2, h / 2), integrate_shells(w / 2, h / 2)}) {
      expect_relative(num.volume, shape.volume(), 1e-10, "volume");
      expect_relative(num.volume * density, mp.mass(), 1e-10, "mass");
      expect_relative(num.i3_per_density * density, mp.principal_moments_body().z(), 1e-10, "I3");
      expect_relative(num.i1_per_density * density, mp.principal_moments_body().x(), 1e-10, "I1");
      expect_relative(num.i1_per_density * density, mp.principal_moments_body().y(), 1e-10, "I2");
    }
    EXPECT_TRUE(mp.is_axisymmetric());
  }
}

TEST(MassProperties, LensGeometryMatchesTheTwoSpheres) {
  const vg::LensShape shape(0.022, 0.009);
  const double a = 0.011, c = 0.0045, d = centre_offset(a, c);
  EXPECT_NEAR(shape.sphere_center_offset(), d, 1e-15);
  EXPECT_NEAR(shape.sphere_radius(), c + d, 1e-15);
  // Points just inside / outside the faces, the rim and the poles.
  const double eps = 1e-9;
  for (double r : {0.0, 0.003, 0.007, 0.0109}) {
    const double t = std::sqrt((c + d) * (c + d) - r * r) - d;
    EXPECT_TRUE(shape.contains(r, 0, t - eps)) << r;
    EXPECT_TRUE(shape.contains(0, -r, -(t - eps))) << r;
    EXPECT_FALSE(shape.contains(r, 0, t + eps)) << r;
    EXPECT_FALSE(shape.contains(0, r, -(t + eps))) << r;
  }
  EXPECT_FALSE(shape.contains(a + eps, 0, 0));
  EXPECT_TRUE(shape.contains(0, a - eps, 0));
}

TEST(MassProperties, SphereLimit) {
  // LensShape needs height < width, so approach c = a: I -> 2/5 m a^2 with error O(1 - c/a).
  const double w = 0.02, density = 2700.0;
  for (double gap : {1e-4, 1e-6, 1e-8}) {
    const vg::LensShape shape(w, w * (1 - gap));
    const vg::MassProperties mp = vg::MassProperties::of_lens(shape, density);
    const double a = w / 2;
    const double sphere_mass = density * 4.0 / 3.0 * M_PI * a * a * a;
    expect_relative(sphere_mass, mp.mass(), 3 * gap, "mass");
    expect_relative(0.4 * sphere_mass * a * a, mp.principal_moments_body().z(), 6 * gap, "I3");
    expect_relative(0.4 * sphere_mass * a * a, mp.principal_moments_body().x(), 6 * gap, "I1");
  }
}

TEST(MassProperties, ThinDiscLimit) {
  // c -> 0: thickness 2t(r) ~ (a^2 - r^2) / R is parabolic, so I3 -> m a^2 / 3 (not the flat
  // disc's m a^2 / 2) and I1 -> I3 / 2 (perpendicular-axis theorem); corrections are O(c^2/a^2).
  const double w = 0.022;
  for (double ratio : {1e-2, 1e-4, 1e-6}) {
    const vg::LensShape shape(w, w * ratio);
    const vg::MassProperties mp = vg::MassProperties::of_lens(shape, 2500.0);
    const double a = w / 2, m = mp.mass();
    const double tol = 2 * ratio * ratio + 1e-13;
    expect_relative(m * a * a / 3, mp.principal_moments_body().z(), tol, "I3");
    expect_relative(mp.principal_moments_body().z() / 2, mp.principal_moments_body().x(), tol,
                    "I1");
  }
}

TEST(MassProperties, WorkedExampleFromDesign) {
  // w 22 mm, h 9 mm, slate: m 4.876 g, I3 2.0239e-7, I1 1.1835e-7 kg m^2 (rounded as printed).
  const vg::MassProperties mp =
      vg::MassProperties::of_lens(vg::LensShape(0.022, 0.009), vg::material_density("slate"));
  EXPECT_NEAR(mp.mass(), 4.876e-3, 0.0005e-3);
  EXPECT_NEAR(mp.principal_moments_body().z(), 2.0239e-7, 0.00005e-7);
  EXPECT_NEAR(mp.principal_moments_body().x(), 1.1835e-7, 0.00005e-7);
  EXPECT_NEAR(mp.principal_moments_body().y(), 1.1835e-7, 0.00005e-7);
}

TEST(MassProperties, Size33SlateWeighsAboutFiveGrams) {
  vg::StoneSpec spec;
  spec.size_number = 33;
  const vg::Stone stone = vg::make_stone(spec);
  EXPECT_NEAR(stone.mass_properties.mass(), 5.0e-3, 0.05e-3);
  // By hand: a = 11 mm, c = 4.6 mm, V = pi c (3a^2 + c^2) / 3 = 1.8505 cm^3, times 2.7 g/cm^3.
  EXPECT_NEAR(stone.mass_properties.mass(), 4.9965e-3, 0.0001e-3);
}

TEST(MassProperties, ExplicitMassOverridesDensityAndScalesTheMoments) {
  const vg::LensShape shape(0.022, 0.0092);
  const vg::MassProperties by_density = vg::MassProperties::of_lens(shape, 2700.0);
  const vg::MassProperties by_mass = vg::MassProperties::of_lens_with_mass(shape, 6.0e-3);
  EXPECT_DOUBLE_EQ(by_mass.mass(), 6.0e-3);
  // Same shape, uniform density: the radii of gyration I / m do not depend on the mass.
  expect_relative(by_density.principal_moments_body().z() / by_density.mass(),
                  by_mass.principal_moments_body().z() / by_mass.mass(), 1e-14, "I3 / m");
  expect_relative(by_density.principal_moments_body().x() / by_density.mass(),
                  by_mass.principal_moments_body().x() / by_mass.mass(), 1e-14, "I1 / m");
}

TEST(MassProperties, InertiaMatricesAreDiagonalAndInverse) {
  const vg::MassProperties mp(1.0, Eigen::Vector3d(2.0, 3.0, 5.0));
  EXPECT_TRUE((mp.inertia_body() * mp.inverse_inertia_body()).isIdentity(1e-15));
  EXPECT_EQ(mp.inertia_body()(1, 1), 3.0);
  EXPECT_EQ(mp.inertia_body()(0, 1), 0.0);
  EXPECT_FALSE(mp.is_axisymmetric());
}

// issue 8: a mass whose moments were subnormal was accepted, and w = L / I then lost digits
// (29.875 for 30). Subnormal masses and moments are refused, naming the moment.
TEST(MassProperties, SubnormalMomentsAreRefused) {
  const vg::LensShape shape(0.022, 0.0092);
  EXPECT_NO_THROW(vg::MassProperties::of_lens_with_mass(shape, 1e-290));
  try {
    vg::MassProperties::of_lens_with_mass(shape, 1e-305);  // moments about 3e-310 kg m^2
    ADD_FAILURE() << "subnormal moments accepted";
  } catch (const vg::InvalidArgument& e) {
    EXPECT_EQ(e.field().rfind("principal moment", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("below the smallest normal double"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(vg::MassProperties(1e-310, Eigen::Vector3d(1, 1, 1)), vg::InvalidArgument);
  // make_stone blames the mass that set them.
  vg::StoneSpec spec;
  spec.mass = 1e-305;
  try {
    vg::make_stone(spec);
    ADD_FAILURE() << "accepted";
  } catch (const vg::InvalidArgument& e) {
    EXPECT_EQ(e.field(), "mass") << e.what();
  }
}
