// Bad input is rejected with an exception whose message names the field and the value, nothing
// is silently clamped, and a failed advance() leaves the caller's state untouched.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "support/physics_reference.h"
#include "support/stone_setup.h"
#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/flight/exact_motion.h"
#include "virtual_go/flight/integrator_registry.h"
#include "virtual_go/geometry/tessellation.h"
#include "virtual_go/go/stone.h"

namespace vg = virtual_go;
using vgtest::contains;
using vgtest::stone_setup;
using vgtest::what_of;

namespace {

const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// Expects InvalidArgument from f with every part in its message.
void expect_rejected(const std::function<void()>& f, const std::vector<std::string>& parts) {
  const std::string what = what_of<vg::InvalidArgument>(f);
  for (const std::string& part : parts) {
    EXPECT_TRUE(contains(what, part)) << "message '" << what << "' lacks '" << part << "'";
  }
}

vg::RigidBodyState good_state(const vg::MotionSetup& setup) {
  vg::RigidBodyState s;
  s.position_world = Eigen::Vector3d(0.1, 0.2, 0.3);
  s.velocity_world = Eigen::Vector3d(0, 0, 2);
  s.orientation = vgtest::to_eigen(vgtest::axis_angle(Eigen::Vector3d(0.1, 0.5, 0.2)));
  return vg::with_angular_velocity_world(setup.model, s, Eigen::Vector3d(5, -3, 20));
}

}  // namespace

TEST(BadInput, LensShapeRejectsNonFiniteAndNonPositiveSizes) {
  expect_rejected([] { vg::LensShape(kNan, 0.009); }, {"width", "nan"});
  expect_rejected([] { vg::LensShape(kInf, 0.009); }, {"width", "inf"});
  expect_rejected([] { vg::LensShape(0.0, 0.009); }, {"width", "0"});
  expect_rejected([] { vg::LensShape(-0.022, 0.009); }, {"width", "-0.022"});
  expect_rejected([] { vg::LensShape(0.022, kNan); }, {"height", "nan"});
  expect_rejected([] { vg::LensShape(0.022, 0.0); }, {"height", "0"});
  expect_rejected([] { vg::LensShape(0.022, -0.009); }, {"height", "-0.009"});
}

TEST(BadInput, HeightMustBeBelowWidth) {
  expect_rejected([] { vg::LensShape(0.022, 0.022); }, {"height", "0.022"});
  expect_rejected([] { vg::LensShape(0.022, 0.0305); }, {"height", "0.0305", "width"});
  vg::StoneSpec spec;
  spec.height = 0.025;
  expect_rejected([&] { vg::make_stone(spec); }, {"height", "0.025"});
}

TEST(BadInput, UnknownNamesAndSizeNumbers) {
  expect_rejected([] { vg::thickness_for_size(41); }, {"size", "41"});
  expect_rejected([] { vg::lens_for_size(0); }, {"size", "0"});
  expect_rejected([] { vg::material_density("marble"); }, {"material", "marble"});
  expect_rejected([] { vg::material_density("Slate"); }, {"material", "Slate"});  // exact names
  expect_rejected([] { vg::motion_model_from_name("wobbly"); }, {"model", "wobbly"});
  expect_rejected([] { vg::make_integrator("verlet", stone_setup()); }, {"integrator", "verlet"});
  vg::StoneSpec spec;
  spec.size_number = 29;
  expect_rejected([&] { vg::make_stone(spec); }, {"size", "29"});
  spec = vg::StoneSpec{};
  spec.material = "plastic";
  expect_rejected([&] { vg::make_stone(spec); }, {"material", "plastic"});
}

TEST(BadInput, MassDensityAndMomentsMustBePositiveAndFinite) {
  vg::StoneSpec spec;
  spec.mass = -0.005;
  expect_rejected([&] { vg::make_stone(spec); }, {"mass", "-0.005"});
  spec.mass = 0.0;
  expect_rejected([&] { vg::make_stone(spec); }, {"mass", "0"});
  spec.mass = kNan;
  expect_rejected([&] { vg::make_stone(spec); }, {"mass", "nan"});
  spec = vg::StoneSpec{};
  spec.density = -2700.0;
  expect_rejected([&] { vg::make_stone(spec); }, {"density", "-2700"});
  spec.density = kInf;
  expect_rejected([&] { vg::make_stone(spec); }, {"density", "inf"});
  spec = vg::StoneSpec{};
  spec.width = -1.0;
  expect_rejected([&] { vg::make_stone(spec); }, {"width", "-1"});
  const vg::LensShape shape(0.022, 0.009);
  expect_rejected([&] { vg::MassProperties::of_lens(shape, 0.0); }, {"density", "0"});
  expect_rejected([&] { vg::MassProperties::of_lens_with_mass(shape, -3.0); }, {"mass", "-3"});
  expect_rejected([] { vg::MassProperties(1.0, Eigen::Vector3d(1.0, -2.0, 1.0)); }, {"Iyy", "-2"});
  expect_rejected([] { vg::MassProperties(1.0, Eigen::Vector3d(1.0, 1.0, kNan)); }, {"Izz", "nan"});
  expect_rejected([] { vg::MassProperties(0.0, Eigen::Vector3d(1.0, 1.0, 1.0)); }, {"mass", "0"});
}

TEST(BadInput, StateMustBeFiniteWithANonZeroQuaternion) {
  const vg::MotionSetup setup = stone_setup();
  vg::RigidBodyState s = good_state(setup);
  s.position_world.y() = kNan;
  expect_rejected([&] { s.validated(); }, {"position", "nan"});
  expect_rejected([&] { vg::RigidBody(setup.model, s); }, {"position", "nan"});
  s = good_state(setup);
  s.velocity_world.z() = -kInf;
  expect_rejected([&] { s.validated(); }, {"velocity", "-inf"});
  s = good_state(setup);
  s.angular_momentum_world.x() = kNan;
  expect_rejected([&] { s.validated(); }, {"angular momentum", "nan"});
  s = good_state(setup);
  s.orientation = Eigen::Quaterniond(0, 0, 0, 0);
  expect_rejected([&] { s.validated(); }, {"orientation", "w 0"});
  expect_rejected([&] { vg::RigidBody(setup.model, s); }, {"orientation"});
  expect_rejected([&] { vg::ExactMotion(setup, s); }, {"orientation"});
  s.orientation = Eigen::Quaterniond(kNan, 0, 0, 1);
  expect_rejected([&] { s.validated(); }, {"orientation", "nan"});
  // Any finite, non-zero size is normalised, however small (found by the service fuzz: w 1e-100
  // was refused as "non-zero" although the README promises this), denormals included.
  for (const double w : {1e-100, 1e-200, 1e-310, 4.9e-324}) {
    s = good_state(setup);
    s.orientation = Eigen::Quaterniond(w, 0, 0, w);  // (w, x, y, z): 90 degrees about z
    const vg::RigidBodyState v = s.validated();
    EXPECT_DOUBLE_EQ(v.orientation.norm(), 1.0) << w;
    EXPECT_NEAR(v.orientation.w(), std::sqrt(0.5), 1e-15) << w;
    EXPECT_NEAR(v.orientation.z(), std::sqrt(0.5), 1e-15) << w;
  }
  expect_rejected(
      [&] {
        vg::with_angular_velocity_world(setup.model, good_state(setup), {1, kNan, 0});
      },
      {"angular velocity", "nan"});
}

TEST(BadInput, GravityTimeAndTessellationParameters) {
  vg::MotionSetup setup = stone_setup();
  setup.gravity_world = Eigen::Vector3d(0, 0, kNan);
  for (const std::string& name : vg::integrator_names()) {
    expect_rejected([&] { vg::make_integrator(name, setup); }, {"gravity", "nan"});
  }
  const vg::ExactMotion motion(stone_setup(), good_state(stone_setup()));
  expect_rejected([&] { motion.state_at(kNan); }, {"time", "nan"});
  const vg::LensShape shape(0.022, 0.009);
  expect_rejected([&] { vg::tessellate_lens(shape, 2, 4); }, {"segments", "2"});
  expect_rejected([&] { vg::tessellate_lens(shape, 16, 0); }, {"rings", "0"});
}

TEST(BadInput, ExactRefusesATriaxialInertia) {
  const vg::MotionSetup triaxial{
      vg::MotionModel(vg::MotionModelKind::rigid_body,
                      vg::MassProperties(1.0, Eigen::Vector3d(1.0, 2.0, 3.0))),
      vg::kStandardGravity};
  expect_rejected([&] { vg::make_integrator("exact", triaxial); }, {"axisymmetric", "2"});
  // The article's model has isotropic inertia, so exact is fine with it for any body.
  const vg::MotionSetup article{
      vg::MotionModel(vg::MotionModelKind::constant_omega, triaxial.model.mass_properties()),
      vg::kStandardGravity};
  EXPECT_NO_THROW(vg::make_integrator("exact", article));
}

TEST(BadInput, BadStepIsRejectedAndTheStateIsUnchanged) {
  for (const auto kind : {vg::MotionModelKind::rigid_body, vg::MotionModelKind::constant_omega}) {
    const vg::MotionSetup setup = stone_setup(kind);
    for (const std::string& name : vg::integrator_names()) {
      SCOPED_TRACE(name + " " + vg::motion_model_name(kind));
      auto integrator = vg::make_integrator(name, setup);
      vg::RigidBodyState s = good_state(setup);
      integrator->advance(s, 1e-3);  // a normal step first, so the integrator has history
      const vg::RigidBodyState before = s;
      for (const auto& [dt, text] : std::vector<std::pair<double, std::string>>{
               {0.0, "0"}, {-1e-3, "-0.001"}, {kNan, "nan"}, {kInf, "inf"}, {-kInf, "-inf"}}) {
        expect_rejected([&] { integrator->advance(s, dt); }, {"dt", text});
        EXPECT_TRUE(s == before) << "dt " << dt;
      }
      integrator->advance(s, 1e-3);  // and it still works
      EXPECT_FALSE(s == before);
    }
  }
}

TEST(BadInput, BadStateIsRejectedByAdvanceAndLeftUnchanged) {
  const vg::MotionSetup setup = stone_setup();
  for (const std::string& name : vg::integrator_names()) {
    SCOPED_TRACE(name);
    auto integrator = vg::make_integrator(name, setup);
    vg::RigidBodyState s = good_state(setup);
    s.position_world.x() = kNan;
    vg::RigidBodyState before = s;
    expect_rejected([&] { integrator->advance(s, 1e-3); }, {"position", "nan"});
    EXPECT_TRUE(s.velocity_world == before.velocity_world &&
                s.orientation.coeffs() == before.orientation.coeffs());
    s = good_state(setup);
    s.angular_momentum_world.z() = kInf;
    expect_rejected([&] { integrator->advance(s, 1e-3); }, {"angular momentum", "inf"});
    // A zero quaternion is no orientation: it must not be stepped (or "normalised") silently.
    s = good_state(setup);
    s.orientation = Eigen::Quaterniond(0, 0, 0, 0);
    before = s;
    expect_rejected([&] { integrator->advance(s, 1e-3); }, {"orientation", "w 0"});
    EXPECT_TRUE(s == before);
    // Also without rotation, where a step has no rotation work to do.
    s.angular_momentum_world.setZero();
    expect_rejected([&] { integrator->advance(s, 1e-3); }, {"orientation", "w 0"});
  }
}

TEST(BadInput, TooLargeARotationPerStepIsAnErrorNotAClamp) {
  // euler and rk4 cannot follow more than 1 rad per step; they say so instead of shrinking dt.
  const vg::MotionSetup setup = stone_setup();
  for (const std::string& name : std::vector<std::string>{"euler", "rk4"}) {
    auto integrator = vg::make_integrator(name, setup);
    vg::RigidBodyState s = good_state(setup);
    const double omega = vg::RigidBody(setup.model, s).angular_velocity_world().norm();
    const double dt = 1.5 / omega;
    const vg::RigidBodyState before = s;
    const std::string what = what_of<vg::IntegrationError>([&] { integrator->advance(s, dt); });
    EXPECT_TRUE(contains(what, name)) << what;
    EXPECT_TRUE(contains(what, "dt")) << what;
    EXPECT_TRUE(contains(what, vg::format_value(dt))) << what;
    EXPECT_TRUE(s == before);
    EXPECT_NO_THROW(integrator->advance(s, 0.9 / omega));
  }
  // splitting and exact take any step.
  for (const std::string& name : std::vector<std::string>{"splitting", "exact"}) {
    auto integrator = vg::make_integrator(name, setup);
    vg::RigidBodyState s = good_state(setup);
    EXPECT_NO_THROW(integrator->advance(s, 10.0)) << name;
  }
}
