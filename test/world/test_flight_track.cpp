// A stone's flight track: samples on a grid whose times carry round-off stay on the closed form
// (written in the test), whatever the grid; the contact search's bookkeeping.
#include <gtest/gtest.h>

#include <cstdint>

#include "support/flight_reference.h"
#include "virtual_go/flight/integrator_registry.h"
#include "virtual_go/world/flight_track.h"
#include "world_test_support.h"

namespace {

using namespace worldtest;

Vector3d flight_velocity(const vgtest::FlightReference& ref, double tau) {
  return ref.v0 + ref.g * tau;
}

TEST(FlightTrack, GridSamplesAreTheClosedForm) {
  const auto mp = stone().mass_properties;
  const vg::MotionSetup setup{model(), kGravity};
  const auto exact = vg::make_integrator("exact", setup);
  const Quaterniond q0(Eigen::AngleAxisd(0.4, Vector3d(1, -2, 0.3).normalized()));
  vg::RigidBodyState s0 =
      with_omega(at(Vector3d(0.1, 0.2, 5.0), q0, Vector3d(1, -0.5, 3)), Vector3d(30, -12, 41));
  const double t0 = 0.123456789;
  vgtest::FlightReference ref{kA, kC, s0.position_world, s0.velocity_world, kGravity, {}};
  ref.top =
      vgtest::AxisymmetricTop{mp.principal_moments_body().x(), mp.principal_moments_body().z(),
                              vgtest::from_eigen(s0.orientation), s0.angular_momentum_world};
  // Grids as a caller builds them: from whole nanoseconds (1 ms and 1/60 s), and a float-stepped
  // 1 ms grid whose differences wander by ulps.
  for (const std::int64_t dt_ns : {std::int64_t{1000000}, std::int64_t{16666667}}) {
    vg::FlightTrack track;
    track.begin(s0, t0);
    vg::RigidBodyState s = s0;
    double t_prev = t0, worst_x = 0, worst_q = 0, worst_ratio = 0;
    const std::int64_t start_ns = 123456789;
    for (int n = 1; n <= 3000; ++n) {
      const double t = static_cast<double>(start_ns + n * dt_ns) * 1e-9;
      ASSERT_TRUE(track.sample(*exact, s, t_prev, t));
      t_prev = t;
      const double tau = t - t0;
      const double error = (s.position_world - ref.position_at(tau)).norm();
      worst_x = std::max(worst_x, error);
      // The cached step may run up to 1e-14 s off the grid time before it is re-anchored, and
      // both sides round to ulps of |x| (a stone falling for 50 s is 12 km down, at 490 m/s).
      const double speed = (flight_velocity(ref, tau)).norm();
      worst_ratio = std::max(worst_ratio,
                             error / (1e-13 + 1e-14 * speed + 1e-14 * ref.position_at(tau).norm()));
      worst_q = std::max(worst_q, vgtest::angle_between(vgtest::from_eigen(s.orientation),
                                                        ref.orientation_at(tau)));
    }
    EXPECT_LE(worst_ratio, 1.0) << dt_ns;
    EXPECT_LE(worst_q, 1e-11) << dt_ns;
    std::printf(
        "[ track   ] dt %lld ns, 3000 samples: position %.1e m (%.2f of its bound), "
        "orientation %.1e rad\n",
        static_cast<long long>(dt_ns), worst_x, worst_ratio, worst_q);
  }
  // Sampling the same time again does nothing.
  vg::FlightTrack track;
  track.begin(s0, t0);
  vg::RigidBodyState s = s0;
  EXPECT_FALSE(track.sample(*exact, s, t0, t0));
  EXPECT_TRUE(s == s0);
}

TEST(FlightTrack, SearchBookkeeping) {
  vg::FlightTrack track;
  track.begin(at(Vector3d(0, 0, 1)), 2.0);
  EXPECT_EQ(track.clear_until_s(), 2.0);
  EXPECT_FALSE(track.contact().has_value());
  EXPECT_EQ(track.contact_time_s(), std::numeric_limits<double>::infinity());
  vg::TimeOfImpact none;
  none.time_s = 3.0;
  track.record_search(none);
  EXPECT_EQ(track.clear_until_s(), 3.0);
  vg::TimeOfImpact hit;
  hit.hit = true;
  hit.time_s = 3.4;
  track.record_search(hit);
  EXPECT_EQ(track.contact_time_s(), 3.4);
  track.begin(at(Vector3d(0, 0, 1)), 5.0);  // a new flight forgets it
  EXPECT_FALSE(track.contact().has_value());
  track.set_free_forever();
  EXPECT_EQ(track.clear_until_s(), std::numeric_limits<double>::infinity());
}

}  // namespace
