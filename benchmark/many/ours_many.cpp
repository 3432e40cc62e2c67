// Ours with many stones: one virtual_go::World holding every stone, sampled on the grid as the
// node samples it (advance_to(k dt), then the states). Today's World has one shape and one mass
// for all its stones and no stone-stone contact (issue 15 builds both): scenes that need
// stones to push each other are refused ("not yet"), and the board of resting stones is run
// with every stone given the black stone's shape and mass (a resting stone's cost does not
// depend on either). When World gains per-stone bodies and stone-stone contact, reset() is the
// one place to change.
#include <optional>

#include "../contact/settings_format.h"
#include "many_method.h"
#include "virtual_go/body/rigid_body.h"
#include "virtual_go/world/world.h"

namespace vg_bench {
namespace {

class OursMany : public ManyMethod {
 public:
  std::string name() const override { return "ours"; }
  bool is_peer() const override { return false; }
  bool has_sleep() const override { return true; }  // exact rest, not a threshold
  std::string version() const override { return "virtual_go core (this tree)"; }

  void reset(const ManyScene& s, double dt) override {
    if (s.needs_stone_contact)
      throw ContactNotRun("not yet: stone-stone contact is not integrated in World");
    if (!s.board_enabled) throw ContactNotRun("not yet: free stones need stone-stone contact");
    const StoneSpec& b = s.black;
    const virtual_go::MotionModel model(
        virtual_go::MotionModelKind::rigid_body,
        virtual_go::MassProperties(b.mass_kg, b.principal_moments_body));
    virtual_go::WorldConfig config(
        virtual_go::MotionSetup{model, s.gravity_world},
        virtual_go::LensShape(2.0 * b.half_width_m, 2.0 * b.half_height_m));
    config.board.size_x_m = s.board.size_x_m;
    config.board.size_y_m = s.board.size_y_m;
    config.board.thickness_m = s.board.thickness_m;
    virtual_go::ContactMaterial m;
    m.restitution = s.material.restitution;
    m.friction = s.material.friction;
    m.rolling_resistance_m = s.material.rolling_resistance_m;
    m.spinning_friction_m = s.material.spinning_friction_m;
    config.board_material = m;
    config.table_material = m;
    std::vector<virtual_go::RigidBodyState> states;
    for (std::size_t i = 0; i < s.stones.size(); ++i) {
      // The black stone's angular momentum for the same angular velocity (zero at rest).
      virtual_go::RigidBodyState st = s.stones[i].initial;
      st.angular_momentum_world =
          virtual_go::with_angular_velocity_world(model, st, s.stones[i].omega_world)
              .angular_momentum_world;
      states.push_back(st);
    }
    world_.reset();
    world_.emplace(config, states, 0.0);
    dt_ = dt;
    k_ = 0;
    events_.clear();
    // The events at t0 (each stone set down at rest comes to rest at once) are not timed.
    world_->advance_to(0.0, events_);
    events_.clear();
    settings_ = {
        {"stones",
         "one World; every stone with the black stone's lens and mass (World has one "
         "body for all stones yet)",
         "include/virtual_go/world/world.h"},
        {"rest",
         "exact: a stone set down flat rests at once; a resting stone is skipped by "
         "advance_to (no integration, no search), its pose frozen bit for bit",
         "docs/physics.md, \"World\""},
        {"sampling", "advance_to(k dt), then state(i)", "docs/physics.md, \"World\""},
    };
  }

  void advance() override {
    ++k_;
    events_.clear();
    world_->advance_to(static_cast<double>(k_) * dt_, events_);
  }

  ContactSample sample(std::size_t i) const override {
    const virtual_go::RigidBodyState& st = world_->state(i);
    ContactSample smp;
    smp.position_world = st.position_world;
    smp.orientation = st.orientation;
    smp.velocity_world = st.velocity_world;
    smp.omega_world =
        world_->setup().model.angular_velocity_world(st.orientation, st.angular_momentum_world);
    return smp;
  }
  bool asleep(std::size_t i) const override { return world_->is_resting(i); }
  std::vector<Setting> settings() const override { return settings_; }

  // Everything the world integrated or searched since its reset (0 while everything rests).
  long work_done() const override {
    const virtual_go::WorldCounters& c = world_->counters();
    return c.flight_steps + c.contact_searches + c.contact_search_steps + c.impacts +
           c.plane_contact_steps + c.plane_contact_rhs + c.nonsmooth_steps + c.nonsmooth_impulses;
  }

 private:
  std::optional<virtual_go::World> world_;
  std::vector<virtual_go::WorldEvent> events_;
  std::vector<Setting> settings_;
  double dt_ = 0.0;
  long k_ = 0;
};

}  // namespace

std::unique_ptr<ManyMethod> make_ours_many() { return std::make_unique<OursMany>(); }

}  // namespace vg_bench
