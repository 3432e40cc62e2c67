// The integrator registry is the one source of the integrators' names, step limits and orders:
// each entry makes an integrator that answers to it, refuses exactly the steps the entry says,
// and README.md's table of integrators restates it. (The orders are measured against physics
// in test_convergence.)
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "support/physics_reference.h"
#include "support/readme_tables.h"
#include "support/stone_setup.h"
#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/formatting.h"
#include "virtual_go/flight/integrator_registry.h"
#include "virtual_go/go/stone.h"

namespace vg = virtual_go;
using vgtest::stone_setup;

namespace {

vg::RigidBodyState spinning(const vg::MotionSetup& setup, const Eigen::Vector3d& omega_world) {
  vg::RigidBodyState s;
  s.orientation = vgtest::to_eigen(vgtest::axis_angle(Eigen::Vector3d(0.4, -0.2, 0.9)));
  return vg::with_angular_velocity_world(setup.model, s, omega_world);
}

}  // namespace

TEST(IntegratorRegistry, EachEntryMakesTheIntegratorItDescribes) {
  std::set<std::string> seen;
  for (const vg::IntegratorInfo& info : vg::integrators().entries()) {
    EXPECT_TRUE(seen.insert(info.name).second) << "twice: " << info.name;
    const auto integrator = vg::make_integrator(info.name, stone_setup());
    EXPECT_EQ(integrator->name(), info.name);
    EXPECT_EQ(&integrator->info(), &info);
    EXPECT_EQ(integrator->max_rotation_per_step(), info.max_rotation_per_step);
    EXPECT_FALSE(info.summary.empty()) << info.name;
    EXPECT_GE(info.order, 0) << info.name;
  }
  EXPECT_EQ(vg::integrator_names().size(), seen.size());
}

TEST(IntegratorRegistry, UnknownNameNamesTheFieldAndListsTheRegistry) {
  try {
    vg::make_integrator("verlet", stone_setup());
    ADD_FAILURE() << "verlet accepted";
  } catch (const vg::InvalidArgument& e) {
    EXPECT_EQ(e.field(), "integrator");
    EXPECT_NE(std::string(e.what()).find("(known: " + vg::join(vg::integrator_names(), " ") + ")"),
              std::string::npos)
        << e.what();
  }
}

TEST(IntegratorRegistry, StepLimitIsTheRegistrysAndNoOther) {
  const vg::MotionSetup setup = stone_setup();
  const Eigen::Vector3d omega(3.0, -4.0, 12.0);  // |omega| = 13 rad/s
  const vg::RigidBodyState s0 = spinning(setup, omega);
  const double speed = vg::RigidBody(setup.model, s0).angular_velocity_world().norm();
  for (const vg::IntegratorInfo& info : vg::integrators().entries()) {
    SCOPED_TRACE(info.name);
    const auto integrator = vg::make_integrator(info.name, setup);
    // Far beyond any explicit method's reach: 100 rad in one step.
    const double huge_rotation = 100.0;
    vg::RigidBodyState s = s0;
    if (std::isinf(info.max_rotation_per_step)) {
      EXPECT_NO_THROW(integrator->advance(s, huge_rotation / speed));
      continue;
    }
    const double limit = info.max_rotation_per_step;
    EXPECT_THROW(integrator->advance(s, limit * 1.001 / speed), vg::IntegrationError);
    EXPECT_TRUE(s == s0);
    EXPECT_NO_THROW(integrator->advance(s, limit * 0.999 / speed));
  }
}

// README.md restates the registry for readers: same names, orders, step limits and summaries.
TEST(IntegratorRegistry, ReadmeTableMatchesTheRegistry) {
  const auto rows = vgtest::readme_table(VG_README, "### Integrators");
  const auto& entries = vg::integrators().entries();
  ASSERT_EQ(rows.size(), entries.size()) << "README.md, \"### Integrators\"";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const vg::IntegratorInfo& info = entries[i];
    ASSERT_EQ(rows[i].size(), 4u) << info.name;
    EXPECT_EQ(rows[i][0], info.name);
    EXPECT_EQ(rows[i][1], info.order == 0 ? "exact" : std::to_string(info.order)) << info.name;
    EXPECT_EQ(rows[i][2], std::isinf(info.max_rotation_per_step)
                              ? "any"
                              : vg::format_value(info.max_rotation_per_step) + " rad")
        << info.name;
    EXPECT_EQ(rows[i][3], info.summary) << info.name;
  }
}
