// Demo of the physics core: prints a stone's mass properties and a short tumbling trajectory.
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/common/formatting.h"
#include "virtual_go/flight/exact_motion.h"
#include "virtual_go/flight/flight_cache.h"
#include "virtual_go/flight/integrator_registry.h"
#include "virtual_go/geometry/rotation.h"
#include "virtual_go/go/stone.h"

namespace vg = virtual_go;

namespace {

const char* const kDefaultIntegrator = "exact";
const char* const kDefaultModel = "rigid_body";

// The choices come from the tables that define them (sizes, materials, integrators, models).
void print_usage() {
  const std::vector<int> sizes = vg::size_numbers();
  std::printf(
      "usage: stone_demo [--size N] [--material NAME] [--integrator NAME] [--model NAME]\n"
      "Prints the mass properties of a Go stone (a biconvex lens, width %.0f mm) and a 1 s\n"
      "trajectory of it tossed upwards while tumbling, with the error against the closed form.\n"
      "  --size N          Japanese size number %d..%d (default %d)\n"
      "  --material NAME   %s (default %s)\n"
      "  --integrator NAME %s (default %s)\n"
      "  --model NAME      %s (default %s)\n",
      vg::kDefaultStoneWidth * 1e3, sizes.front(), sizes.back(), vg::kDefaultSizeNumber,
      vg::join(vg::material_names(), ", ").c_str(), vg::StoneSpec{}.material.c_str(),
      vg::join(vg::integrator_names(), ", ").c_str(), kDefaultIntegrator,
      vg::join(vg::motion_models().names(), ", ").c_str(), kDefaultModel);
}

}  // namespace

int main(int argc, char** argv) {
  vg::StoneSpec spec;
  spec.size_number = vg::kDefaultSizeNumber;
  std::string integrator_name = kDefaultIntegrator, model_name = kDefaultModel;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      print_usage();
      return 0;
    }
    if (i + 1 >= argc) {
      std::fprintf(stderr, "stone_demo: %s needs a value (see --help)\n", arg.c_str());
      return 2;
    }
    const std::string value = argv[++i];
    try {
      if (arg == "--size") {
        spec.size_number = std::stoi(value);
      } else if (arg == "--material") {
        spec.material = value;
      } else if (arg == "--integrator") {
        integrator_name = value;
      } else if (arg == "--model") {
        model_name = value;
      } else {
        std::fprintf(stderr, "stone_demo: unknown option %s (see --help)\n", arg.c_str());
        return 2;
      }
    } catch (const std::exception&) {
      std::fprintf(stderr, "stone_demo: %s needs a whole number, got '%s'\n", arg.c_str(),
                   value.c_str());
      return 2;
    }
  }
  try {
    const vg::Stone stone = vg::make_stone(spec);
    const Eigen::Vector3d& moments = stone.mass_properties.principal_moments_body();
    std::printf("Go stone: size %d, %s, width %.1f mm, height %.1f mm\n", *spec.size_number,
                spec.material.c_str(), stone.shape.width() * 1e3, stone.shape.height() * 1e3);
    std::printf("  volume       %.4e m^3 (%.3f cm^3)\n", stone.shape.volume(),
                stone.shape.volume() * 1e6);
    std::printf("  mass         %.4e kg (%.3f g)\n", stone.mass_properties.mass(),
                stone.mass_properties.mass() * 1e3);
    std::printf("  I1 = I2      %.4e kg m^2 (transverse)\n", moments.x());
    std::printf("  I3           %.4e kg m^2 (about the symmetry axis, body z)\n", moments.z());

    const vg::MotionSetup setup{
        vg::MotionModel(vg::motion_model_from_name(model_name), stone.mass_properties),
        vg::kStandardGravity};
    vg::RigidBodyState state;
    state.position_world = Eigen::Vector3d(0.0, 0.0, 0.5);
    state.velocity_world = Eigen::Vector3d(0.0, 0.0, 4.0);
    state.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()));
    state = vg::with_angular_velocity_world(setup.model, state, Eigen::Vector3d(20, 5, 40));

    const auto integrator = vg::make_integrator(integrator_name, setup);
    vg::FlightCache cache;  // the stone's: the exact integrator continues its closed form
    const vg::ExactMotion exact(setup, state);
    const double dt_s = 1.0 / 600.0;
    std::printf("\nTrajectory (%s model, %s integrator, dt %.5f s; error vs closed form)\n",
                model_name.c_str(), integrator_name.c_str(), dt_s);
    std::printf("%6s %9s %9s %9s   %8s %8s %8s %8s   %10s %9s\n", "t [s]", "x [m]", "y [m]",
                "z [m]", "qw", "qx", "qy", "qz", "|w| rad/s", "err [rad]");
    for (int n = 0; n <= 600; ++n) {
      if (n % 60 == 0) {
        const vg::RigidBody body(setup.model, state);
        const auto& q = state.orientation;
        std::printf("%6.3f %9.5f %9.5f %9.5f   %8.5f %8.5f %8.5f %8.5f   %10.4f %9.2e\n", n * dt_s,
                    state.position_world.x(), state.position_world.y(), state.position_world.z(),
                    q.w(), q.x(), q.y(), q.z(), body.angular_velocity_world().norm(),
                    vg::orientation_error(exact.state_at(n * dt_s).orientation, q));
      }
      if (n < 600) integrator->advance(state, dt_s, cache);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stone_demo: %s\n", e.what());
    return 1;
  }
  return 0;
}
