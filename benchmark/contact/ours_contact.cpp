// Ours: the virtual_go core's event-driven contact (exact flight between exact times of impact,
// Stronge impacts, sustained contact in constraint coordinates, exact rest), behind the same
// interface as the peers.
//
// The contact core (world/ over contact/, geometry/ and go/board.h) is not merged yet, so
// reset() refuses with "not run: contact core not merged yet" and the tables say so. When it
// lands, this adapter is the only file to change (and the core's new sources are picked up by
// benchmark/CMakeLists.txt's glob). What each call must do:
//
// reset(scenario, dt):
//   - board: virtual_go::BoardGeometry with size_x_m, size_y_m, thickness_m from
//     scenario.board (top at z = 0, centred on the origin, table at z = -thickness);
//   - materials: virtual_go::ContactMaterial for the board and for the table from
//     scenario.board_material and scenario.table_material (restitution, friction,
//     rolling_resistance_m, spinning_friction_m: the same field names);
//   - the stone: its lens (2 * half_width_m wide, 2 * half_height_m thick), a
//     virtual_go::MotionModel(rigid_body, MassProperties(mass_kg, principal_moments_body)),
//     gravity scenario.gravity_world, and the initial state scenario.initial (a
//     RigidBodyState that already carries the angular momentum);
//   - build the world from these, add the stone, remember dt and set the grid index k = 0
//     and the counters to 0;
//   - scenario.rotation_frozen: throw ContactNotRun unless the world offers a test option
//     that holds the rotation.
// advance():
//   - ++k; advance the world to t = k * dt (world time in seconds; the world goes through
//     every event up to t in order and returns them); add the number of events returned, and
//     of impacts among them, to the counters.
// sample():
//   - the stone's exact state at t = k * dt: position, orientation, velocity, and the world
//     angular velocity from the state's angular momentum (MotionModel::angular_velocity_world).
// asleep():
//   - whether the world put the stone to sleep (exact rest: frozen, no work per advance).
// counters():
//   - events and impacts since reset(), and the sustained-contact integrator's right-hand-side
//     evaluations if the world exposes them (cost per event = run time / events).
// settings():
//   - the materials, the Zeno cut-off (1 um) and the integrator tolerances as run.
#include "contact_method.h"

namespace vg_bench {
namespace {

class OursContact : public ContactMethod {
 public:
  std::string name() const override { return "ours"; }
  std::string family() const override { return "ours"; }
  std::string variant() const override { return "events"; }
  bool is_peer() const override { return false; }
  std::string version() const override { return "virtual_go core (this tree)"; }
  void reset(const ContactScenario&, double) override {
    throw ContactNotRun("not run: contact core not merged yet");
  }
  void advance() override {}
  ContactSample sample() const override { return {}; }
  bool asleep() const override { return false; }
  std::vector<Setting> settings() const override {
    return {{"contact law", "not run: contact core not merged yet", ""}};
  }
};

class ClosedFormDrop : public ContactMethod {
 public:
  std::string name() const override { return "closed_form"; }
  std::string family() const override { return "reference"; }
  std::string variant() const override { return "closed form"; }
  bool is_peer() const override { return false; }
  std::string version() const override { return "the flat drop's closed form"; }
  void reset(const ContactScenario& s, double dt) override {
    if (!s.drop) throw ContactNotRun("not run: no closed form for this scenario");
    drop_ = *s.drop;
    c_ = s.stone.half_height_m;
    x0_ = s.initial.position_world;
    dt_ = dt;
    k_ = 0;
  }
  void advance() override { ++k_; }
  ContactSample sample() const override {
    const double t = static_cast<double>(k_) * dt_;
    ContactSample smp;
    smp.position_world = Eigen::Vector3d(x0_.x(), x0_.y(), c_ + drop_.height_at(t));
    smp.velocity_world = Eigen::Vector3d(0.0, 0.0, drop_.velocity_at(t));
    return smp;
  }
  bool asleep() const override {
    return static_cast<double>(k_) * dt_ >= drop_.rest_time_with_cutoff_s(1e-6);
  }
  ContactCounters counters() const override { return {}; }
  std::vector<Setting> settings() const override { return {}; }

 private:
  FlatDropReference drop_;
  double c_ = 0.0, dt_ = 0.0;
  Eigen::Vector3d x0_ = Eigen::Vector3d::Zero();
  long k_ = 0;
};

}  // namespace

std::unique_ptr<ContactMethod> make_ours_contact() { return std::make_unique<OursContact>(); }
std::unique_ptr<ContactMethod> make_closed_form_drop() {
  return std::make_unique<ClosedFormDrop>();
}

}  // namespace vg_bench
