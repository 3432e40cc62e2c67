// Fuzz of the core's public entry points with random finite and non-finite inputs (fixed seed,
// bounded count): every call either succeeds with a finite state and a unit quaternion, or
// throws the documented virtual_go::InvalidArgument / IntegrationError. Nothing else.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <typeinfo>

#include "support/stress_cases.h"
#include "virtual_go/common/validation.h"
#include "virtual_go/flight/exact_motion.h"
#include "virtual_go/flight/flight_cache.h"
#include "virtual_go/geometry/tessellation.h"

namespace {

using namespace stress;

class Fuzzer {
 public:
  explicit Fuzzer(std::uint64_t seed) : rng_(seed) {}

  // Mostly plausible values, sometimes the edges of double: 0, -0, denormal, huge, inf, NaN.
  double number(double typical = 1.0) {
    const int kind = integer(0, 19);
    switch (kind) {
      case 0:
        return 0.0;
      case 1:
        return -0.0;
      case 2:
        return std::numeric_limits<double>::denorm_min();
      case 3:
        return (coin() ? 1 : -1) * 1e300;
      case 4:
        return std::numeric_limits<double>::infinity();
      case 5:
        return -std::numeric_limits<double>::infinity();
      case 6:
        return std::numeric_limits<double>::quiet_NaN();
      case 7:
        return (coin() ? 1 : -1) * std::pow(10.0, uniform(-30.0, 30.0));
      default:
        return typical * uniform(-2.0, 2.0);
    }
  }
  // Finite and positive most of the time.
  double positive(double typical) {
    return integer(0, 3) == 0 ? number(typical) : typical * std::pow(10.0, uniform(-3.0, 3.0));
  }
  Eigen::Vector3d vector(double typical = 1.0) {
    if (integer(0, 2) > 0)
      return typical * Eigen::Vector3d(uniform(-2, 2), uniform(-2, 2), uniform(-2, 2));
    return Eigen::Vector3d(number(typical), number(typical), number(typical));
  }
  Eigen::Quaterniond quaternion() {
    if (integer(0, 3) > 0) {
      return Eigen::Quaterniond(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    }
    return Eigen::Quaterniond(number(), number(), number(), number());
  }
  std::string name(const std::vector<std::string>& good) {
    if (integer(0, 4) > 0) return good[integer(0, static_cast<int>(good.size()) - 1)];
    static const std::vector<std::string> bad{"", "EULER", "exact ", "slate\n", "nan", "rk5"};
    return bad[integer(0, static_cast<int>(bad.size()) - 1)];
  }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  bool coin() { return integer(0, 1) == 1; }

 private:
  std::mt19937_64 rng_;
};

struct Tally {
  int ok = 0, invalid = 0, refused = 0;
};

// Runs one call; it may succeed (its own checks run inside) or throw a documented error. Every
// InvalidArgument names the input to blame in field() (one of `fields` when given), so that a
// caller can map it to its own names without reading the message.
template <class F>
void call(const char* what, int case_index, Tally& tally, F&& f,
          const std::vector<std::string>& fields = {}) {
  try {
    f();
    ++tally.ok;
  } catch (const vg::InvalidArgument& e) {
    ++tally.invalid;
    EXPECT_FALSE(e.field().empty()) << what << " (case " << case_index << "): " << e.what();
    if (!fields.empty()) {
      EXPECT_NE(std::find(fields.begin(), fields.end(), e.field()), fields.end())
          << what << " (case " << case_index << ") blamed '" << e.field() << "': " << e.what();
    }
  } catch (const vg::IntegrationError& e) {
    ++tally.refused;
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << " (case " << case_index << ") threw an undocumented "
                  << typeid(e).name() << ": " << e.what();
  }
}

void expect_good(const vg::RigidBodyState& s, const char* what, int case_index) {
  EXPECT_TRUE(unit_and_finite(s, 1e-9))
      << what << " (case " << case_index << ") returned a non-finite or non-unit state: x "
      << s.position_world.transpose() << ", q " << s.orientation.coeffs().transpose() << ", v "
      << s.velocity_world.transpose() << ", L " << s.angular_momentum_world.transpose();
}

constexpr std::uint64_t kSeed = 0x5eed2024;
constexpr int kCases = 4000;

TEST(StressFuzz, LensShapeMassAndModel) {
  Fuzzer fz(kSeed);
  Tally tally;
  for (int i = 0; i < kCases; ++i) {
    call("LensShape", i, tally, [&] {
      const double w = fz.positive(0.022), h = fz.positive(0.009);
      const vg::LensShape shape(w, h);
      // A shape is not a state: an absurd size may overflow its volume, never make it NaN.
      const double volume = shape.volume();
      EXPECT_FALSE(std::isnan(volume)) << "case " << i << ": width " << w << " height " << h;
      // Where nothing over- or underflows, the lens lies between the double cone on its rim
      // and the cylinder around it: pi a^2 h / 3 <= V <= pi a^2 h.
      const double cylinder = M_PI * 0.25 * w * w * h;
      if (std::isnormal(volume) && std::isnormal(cylinder)) {
        EXPECT_GE(volume, cylinder / 3.0 * (1.0 - 1e-12)) << "case " << i << ": " << w << " " << h;
        EXPECT_LE(volume, cylinder * (1.0 + 1e-12)) << "case " << i << ": " << w << " " << h;
      }
    });
    call("make_stone", i, tally,
         [&] {
           vg::StoneSpec spec;
           if (fz.coin()) spec.size_number = fz.integer(-5, 45);
           if (fz.coin()) spec.width = fz.positive(0.022);
           if (fz.integer(0, 3) == 0) spec.height = fz.positive(0.009);
           spec.material = fz.name(vg::material_names());
           if (fz.integer(0, 3) == 0) spec.density = fz.positive(2700.0);
           if (fz.integer(0, 3) == 0) spec.mass = fz.positive(0.005);
           const vg::Stone stone = vg::make_stone(spec);
           const vg::MassProperties& mp = stone.mass_properties;
           EXPECT_TRUE(std::isfinite(mp.mass()) && mp.mass() > 0.0) << i;
           EXPECT_TRUE(mp.principal_moments_body().allFinite() &&
                       (mp.principal_moments_body().array() > 0.0).all())
               << i;
         },
         {"size_number", "width", "height", "material", "density", "mass"});
    call("MassProperties", i, tally, [&] {
      const double mass = fz.positive(0.005);
      const Eigen::Vector3d moments(fz.positive(1e-7), fz.positive(1e-7), fz.positive(2e-7));
      const vg::MassProperties mp(mass, moments);
      const vg::MotionModel model(
          fz.coin() ? vg::MotionModelKind::rigid_body : vg::MotionModelKind::constant_omega, mp);
      vg::RigidBodyState s;
      s.position_world = fz.vector();
      s.orientation = fz.quaternion();
      s.velocity_world = fz.vector();
      const Eigen::Vector3d omega = fz.vector(50.0);
      const vg::RigidBodyState with = vg::with_angular_velocity_world(model, s, omega);
      expect_good(with, "with_angular_velocity_world", i);
      // Derived quantities (energy, omega) of absurd inputs (1e300 kg m^2) may overflow; the
      // state itself must be finite, and a body is built from it only after validation.
      const vg::RigidBody body(model, with);
      EXPECT_TRUE(body.state().orientation.coeffs().allFinite())
          << "case " << i << ": mass " << mass << " moments " << moments.transpose() << " omega "
          << omega.transpose();
    });
    call("names", i, tally, [&] {
      (void)vg::motion_model_from_name(fz.name({"constant_omega", "rigid_body"}));
      (void)vg::material_density(fz.name(vg::material_names()));
      (void)vg::thickness_for_size(fz.integer(-100, 100));
    });
    call("tessellate_lens", i, tally, [&] {
      const vg::LensShape shape(0.022, 0.009);
      const vg::TriangleMesh mesh =
          vg::tessellate_lens(shape, fz.integer(-3, 40), fz.integer(-3, 12));
      for (const Eigen::Vector3d& v : mesh.vertices) ASSERT_TRUE(v.allFinite()) << i;
    });
  }
  EXPECT_GT(tally.ok, kCases);            // most calls must get through
  EXPECT_GT(tally.invalid, kCases / 10);  // and the bad ones must be rejected
}

TEST(StressFuzz, StatesIntegratorsAndClosedForm) {
  Fuzzer fz(kSeed + 1);
  Tally tally;
  const vg::MassProperties stone = slate33();
  for (int i = 0; i < kCases; ++i) {
    const vg::MassProperties mp = fz.integer(0, 3) == 0
                                      ? vg::MassProperties(0.005, Eigen::Vector3d(1e-7, 2e-7, 3e-7))
                                      : stone;
    const vg::MotionModel model(
        fz.coin() ? vg::MotionModelKind::rigid_body : vg::MotionModelKind::constant_omega, mp);
    const vg::MotionSetup setup{model,
                                fz.integer(0, 5) == 0 ? fz.vector(10.0) : vg::kStandardGravity};
    vg::RigidBodyState s;
    s.position_world = fz.vector();
    s.orientation = fz.quaternion();
    s.velocity_world = fz.vector(3.0);
    s.angular_momentum_world =
        fz.integer(0, 5) == 0
            ? fz.vector(1e-5)
            : Eigen::Vector3d(fz.uniform(-1, 1), fz.uniform(-1, 1), fz.uniform(-1, 1)) * 1e-5;
    call("RigidBodyState::validated", i, tally,
         [&] { expect_good(s.validated(), "validated", i); });
    call("make_integrator/advance", i, tally, [&] {
      const auto integrator = vg::make_integrator(fz.name(vg::integrator_names()), setup);
      vg::FlightCache cache;  // one flight, also across refused steps
      vg::RigidBodyState state = s;
      // Raw on purpose: a non-unit quaternion must be normalised, a zero or non-finite one refused.
      for (int k = 0; k < 5; ++k) {
        const double dt = fz.integer(0, 3) == 0 ? fz.number(0.01) : fz.positive(1.0 / 60.0);
        const vg::RigidBodyState before = state;
        try {
          integrator->advance(state, dt, cache);
        } catch (...) {
          EXPECT_TRUE(state == before) << "advance changed the state before throwing, case " << i;
          throw;
        }
        expect_good(state, "advance", i);
      }
    });
    call("ExactMotion::state_at", i, tally, [&] {
      const vg::ExactMotion motion(setup, s);
      const double t = fz.integer(0, 2) == 0 ? fz.number(100.0) : fz.uniform(-100.0, 100.0);
      expect_good(motion.state_at(t), "state_at", i);
      EXPECT_TRUE(motion.left_rotation(t).coeffs().allFinite()) << i;
    });
    call("rotation_exp", i, tally, [&] {
      const Eigen::Quaterniond q = vg::rotation_exp(fz.vector(fz.coin() ? 1.0 : 1e6));
      EXPECT_TRUE(q.coeffs().allFinite() && std::abs(q.norm() - 1.0) < 1e-12) << i;
    });
    call("orientation_error", i, tally, [&] {
      const Eigen::Quaterniond p(fz.uniform(-1, 1), fz.uniform(-1, 1), fz.uniform(-1, 1), 1.0);
      // A measurement helper: finite inputs only (NaN in, NaN out is its documented nature).
      const Eigen::Quaterniond q = fz.quaternion();
      if (!q.coeffs().allFinite()) return;
      const double e = vg::orientation_error(p, q);
      EXPECT_TRUE(e >= 0.0 && e <= M_PI) << i;
      // Where q can be normalised, the same angle from the textbook 2 acos |<p, q>| of the unit
      // quaternions (less accurate near 0, ~1e-8 rad there).
      const double norm = q.coeffs().norm();
      if (norm > 1e-150 && norm < 1e150) {
        const double dot = std::abs(p.coeffs().normalized().dot(q.coeffs() / norm));
        EXPECT_NEAR(e, 2.0 * std::acos(std::min(1.0, dot)), 1e-6) << i;
      }
    });
  }
  EXPECT_GT(tally.ok, kCases);
  EXPECT_GT(tally.invalid + tally.refused, kCases / 10);
}

}  // namespace
