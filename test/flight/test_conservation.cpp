// Conservation laws of the torque-free tumbling stone under gravity, per integrator: world
// angular momentum L (gravity exerts no torque about the centre of mass), the body-axis
// component L . n (constant for an axisymmetric body), rotational energy 1/2 L . omega and
// total energy 1/2 m v^2 - m g . x + E_rot. Reports final and maximum error over the run to tell
// drift from bounded oscillation.
#include <gtest/gtest.h>

#include <cstdio>

#include "support/physics_reference.h"
#include "virtual_go/body/rigid_body.h"
#include "virtual_go/flight/flight_cache.h"
#include "virtual_go/flight/integrator_registry.h"
#include "virtual_go/go/stone.h"

namespace vg = virtual_go;

namespace {

struct Errors {
  double rot_energy_max = 0, rot_energy_final = 0;      // relative
  double rot_energy_max_first_half = 0;                 // relative
  double total_energy_max = 0, axial_momentum_max = 0;  // relative
  bool momentum_bitwise_constant = true;
};

vg::MotionSetup setup_for(const Eigen::Vector3d& inertia) {
  return {vg::MotionModel(vg::MotionModelKind::rigid_body, vg::MassProperties(5e-3, inertia)),
          vg::kStandardGravity};
}

Errors run(const std::string& name, const vg::MotionSetup& setup, double dt, double t_end) {
  const Eigen::Vector3d inertia = setup.model.mass_properties().principal_moments_body();
  const double m = setup.model.mass_properties().mass();
  vg::RigidBodyState s;
  s.position_world = Eigen::Vector3d(0, 0, 0.5);
  s.velocity_world = Eigen::Vector3d(0.3, 0, 4.0);
  s.orientation = vgtest::to_eigen(vgtest::axis_angle(Eigen::Vector3d(0.3, 0.2, -0.5)));
  const Eigen::Vector3d omega_body(15.0, -8.0, 25.0);
  s.angular_momentum_world =
      vgtest::rotate(vgtest::from_eigen(s.orientation), inertia.cwiseProduct(omega_body));
  const Eigen::Vector3d l0 = s.angular_momentum_world;

  // Energies computed here from the state: E_rot = 1/2 L_b . I^-1 L_b.
  auto rot_energy = [&](const vg::RigidBodyState& st) {
    const Eigen::Vector3d lb = vgtest::rotate(vgtest::qconj(vgtest::from_eigen(st.orientation)),
                                              st.angular_momentum_world);
    return 0.5 * lb.dot(lb.cwiseQuotient(inertia));
  };
  auto total_energy = [&](const vg::RigidBodyState& st) {
    return 0.5 * m * st.velocity_world.squaredNorm() + m * 9.80665 * st.position_world.z() +
           rot_energy(st);
  };
  auto axial = [&](const vg::RigidBodyState& st) {
    return st.angular_momentum_world.dot(st.orientation * Eigen::Vector3d::UnitZ());
  };
  const double e_rot0 = rot_energy(s), e0 = total_energy(s), axial0 = axial(s);

  auto integrator = vg::make_integrator(name, setup);
  vg::FlightCache cache;  // the stone's own, carried from step to step
  Errors err;
  const int n = static_cast<int>(std::lround(t_end / dt));
  for (int i = 1; i <= n; ++i) {
    integrator->advance(s, dt, cache);
    const double de = std::abs(rot_energy(s) / e_rot0 - 1);
    err.rot_energy_max = std::max(err.rot_energy_max, de);
    if (2 * i <= n) err.rot_energy_max_first_half = err.rot_energy_max;
    err.rot_energy_final = de;
    err.total_energy_max = std::max(err.total_energy_max, std::abs(total_energy(s) / e0 - 1));
    err.axial_momentum_max =
        std::max(err.axial_momentum_max, std::abs(axial(s) - axial0) / l0.norm());
    err.momentum_bitwise_constant &= s.angular_momentum_world == l0;
  }
  std::printf(
      "%-9s dt %-7g T %g s: E_rot rel err max %.2e (first half %.2e, final %.2e), E_total max "
      "%.2e, L.n max %.2e\n",
      name.c_str(), dt, t_end, err.rot_energy_max, err.rot_energy_max_first_half,
      err.rot_energy_final, err.total_energy_max, err.axial_momentum_max);
  return err;
}

const Eigen::Vector3d kStoneInertia =
    vg::make_stone(vg::StoneSpec{}).mass_properties.principal_moments_body();

}  // namespace

TEST(Conservation, WorldAngularMomentumIsHeldExactlyByEveryIntegrator) {
  // L is primary state and no torque acts, so no integrator may touch it, not even by round-off.
  for (const std::string& name : vg::integrator_names()) {
    EXPECT_TRUE(run(name, setup_for(kStoneInertia), 1e-3, 1.0).momentum_bitwise_constant) << name;
  }
}

TEST(Conservation, ExactConservesEverythingToRoundOff) {
  const Errors e = run("exact", setup_for(kStoneInertia), 1e-3, 5.0);
  EXPECT_LT(e.rot_energy_max, 1e-13);
  EXPECT_LT(e.total_energy_max, 1e-13);
  EXPECT_LT(e.axial_momentum_max, 1e-13);
}

TEST(Conservation, SplittingEnergyErrorIsBoundedAndSecondOrder) {
  // Symplectic: the energy error oscillates at O(h^2) without drift; L . n stays exact for the
  // axisymmetric stone only up to O(h^2) as well, since the axis-1 and axis-2 flows are split.
  const Errors coarse = run("splitting", setup_for(kStoneInertia), 2e-3, 20.0);
  const Errors fine = run("splitting", setup_for(kStoneInertia), 1e-3, 20.0);
  const double ratio = coarse.rot_energy_max / fine.rot_energy_max;
  std::printf("splitting: energy error ratio on halving dt %.3f (h^2: 4)\n", ratio);
  EXPECT_NEAR(ratio, 4.0, 0.4);
  // No drift: the second half of a 20 s run (~ 100 precession periods) adds nothing.
  EXPECT_LT(fine.rot_energy_max, 1.05 * fine.rot_energy_max_first_half);
  EXPECT_LT(fine.rot_energy_max, 1e-3);
  EXPECT_LT(fine.axial_momentum_max, 1e-3);
  // Translation is exact; rotation is ~1e-3 of the total energy here, so its error shows scaled.
  EXPECT_LT(fine.total_energy_max, 2e-8);
}

TEST(Conservation, SplittingBoundsEnergyForATriaxialBodyToo) {
  // Intermediate-axis tumbling (Dzhanibekov) is the hard case; the error must stay bounded.
  const vg::MotionSetup triaxial = setup_for(Eigen::Vector3d(1e-7, 2e-7, 3e-7));
  const Errors coarse = run("splitting", triaxial, 2e-3, 20.0);
  const Errors fine = run("splitting", triaxial, 1e-3, 20.0);
  EXPECT_NEAR(coarse.rot_energy_max / fine.rot_energy_max, 4.0, 0.6);
  EXPECT_LT(fine.rot_energy_max, 1.05 * fine.rot_energy_max_first_half);
  EXPECT_LT(fine.rot_energy_max, 1e-3);
}

TEST(Conservation, Rk4DriftsSlightly) {
  // Not symplectic: a small, fourth-order drift.
  const Errors coarse = run("rk4", setup_for(kStoneInertia), 2e-3, 5.0);
  const Errors fine = run("rk4", setup_for(kStoneInertia), 1e-3, 5.0);
  EXPECT_LT(fine.rot_energy_max, 1e-6);
  EXPECT_LT(fine.axial_momentum_max, 1e-6);
  EXPECT_GT(coarse.rot_energy_max / fine.rot_energy_max, 12.0);  // ~16 for h^4
}

TEST(Conservation, ArticleEulerDriftsAtFirstOrder) {
  // The article's Euler turns q about the omega of the start of each step, frozen: for a
  // tumbling body the energy and L . n drift steadily (here ~9% and ~8% after 1 s at 1 ms) and,
  // while small, in proportion to t dt. Over seconds the error saturates at order one (the
  // energy can only range between |L|^2 / 2 I3 and |L|^2 / 2 I1 at fixed L).
  const Errors coarse = run("euler", setup_for(kStoneInertia), 2e-4, 0.2);
  const Errors fine = run("euler", setup_for(kStoneInertia), 1e-4, 0.2);
  const double ratio = coarse.rot_energy_max / fine.rot_energy_max;
  std::printf("euler: energy error ratio on halving dt %.3f (h: 2)\n", ratio);
  EXPECT_NEAR(ratio, 2.0, 0.1);
  // Drift, not oscillation: the error keeps growing, about linearly in t.
  EXPECT_NEAR(fine.rot_energy_final / fine.rot_energy_max_first_half, 2.0, 0.4);
  EXPECT_GT(fine.rot_energy_max, 1e-4);  // clearly visible, unlike the exact flows
  const Errors long_run = run("euler", setup_for(kStoneInertia), 1e-3, 1.0);
  EXPECT_GT(long_run.rot_energy_max, 1e-2);
  EXPECT_GT(long_run.axial_momentum_max, 1e-2);
}
