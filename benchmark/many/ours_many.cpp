// Ours with many stones: one virtual_go::World holding every stone, sampled on the grid as the
// node samples it (advance_to(k dt), then the states). Stone-stone contact is switched on
// explicitly (WorldConfig::stone_contact, the core's default too), and each
// stone gets its colour's body exactly as the scene gives it to the peers: the config's body is
// the scene's black stone, a second body the scene's white stone. One contact law for every
// pair, as for the peers (board, table, stone-stone).
#include <optional>

#include "../contact/settings_format.h"
#include "many_method.h"
#include "virtual_go/body/rigid_body.h"
#include "virtual_go/world/world.h"

namespace vg_bench {
namespace {

class OursMany : public ManyMethod {
 public:
  OursMany(double nonsmooth_step_s, bool joint_solve, bool hold_check)
      : nonsmooth_step_s_(nonsmooth_step_s), joint_solve_(joint_solve), hold_check_(hold_check) {}
  std::string name() const override { return "ours"; }
  bool is_peer() const override { return false; }
  bool has_sleep() const override { return true; }  // exact rest, not a threshold
  std::string version() const override { return "virtual_go core (this tree)"; }

  void reset(const ManyScene& s, double dt) override {
    const auto model_of = [](const StoneSpec& spec) {
      return virtual_go::MotionModel(
          virtual_go::MotionModelKind::rigid_body,
          virtual_go::MassProperties(spec.mass_kg, spec.principal_moments_body));
    };
    const auto shape_of = [](const StoneSpec& spec) {
      return virtual_go::LensShape(2.0 * spec.half_width_m, 2.0 * spec.half_height_m);
    };
    virtual_go::WorldConfig config(virtual_go::MotionSetup{model_of(s.black), s.gravity_world},
                                   shape_of(s.black));
    config.board_enabled = s.board_enabled;
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
    config.stone_material = m;
    config.stone_contact = true;
    if (nonsmooth_step_s_ > 0.0) config.options.nonsmooth.step_s = nonsmooth_step_s_;
    config.options.nonsmooth.joint_solve = joint_solve_;
    config.options.nonsmooth.hold_check = hold_check_;
    world_.reset();
    world_.emplace(config, std::vector<virtual_go::RigidBodyState>{}, 0.0);
    // Body 0 is the config's (the scene's black stone); body 1 the scene's white stone.
    const std::size_t white =
        world_->add_body(virtual_go::WorldBody{model_of(s.white), shape_of(s.white), std::nullopt});
    events_.clear();
    for (std::size_t i = 0; i < s.stones.size(); ++i) {
      const bool is_black = s.stones[i].colour == Colour::black;
      const virtual_go::MotionModel model = model_of(is_black ? s.black : s.white);
      // The stone's own angular momentum for the scene's angular velocity (zero at rest).
      const virtual_go::RigidBodyState st = virtual_go::with_angular_velocity_world(
          model, s.stones[i].initial, s.stones[i].omega_world);
      world_->add_stone(is_black ? 0 : white, st, 0.0, events_);
    }
    dt_ = dt;
    k_ = 0;
    // The events at t0 (each stone set down at rest comes to rest at once) are not timed.
    world_->advance_to(0.0, events_);
    events_.clear();
    settings_ = {
        {"stones",
         "one World with stone-stone contact on (WorldConfig::stone_contact); two bodies: the "
         "scene's black and white stones (lens, mass, moments)",
         "include/virtual_go/world/world.h"},
        {"stone-stone contact",
         "exact pair time of impact between closed-form motions, Stronge's two-body impact "
         "(energetic e*, Coulomb friction through the impulse); a stone in contact or a "
         "resting partner: an island of the fixed-step nonsmooth scheme (Moreau-Jean, e = 0, "
         "h = " +
             num(world_->config().options.nonsmooth.step_s) + " s" +
             (joint_solve_ ? "; the joint solve, NonsmoothContactOptions::joint_solve, on" : "") +
             (hold_check_ ? "; a rest the contacts cannot hold refused and the joint solve on "
                            "from there (NonsmoothContactOptions::hold_check)"
                          : "; the hold check, NonsmoothContactOptions::hold_check, off") +
             ")",
         "docs/physics.md, \"Stone-stone contact in the world\""},
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
    smp.omega_world = world_->body_model(world_->body_of(i))
                          .setup()
                          .model.angular_velocity_world(st.orientation, st.angular_momentum_world);
    return smp;
  }
  bool asleep(std::size_t i) const override { return world_->is_resting(i); }
  std::vector<Setting> settings() const override { return settings_; }

  // Everything the world integrated or searched since its reset (0 while everything rests),
  // pair searches and gap checks included.
  long work_done() const override {
    const virtual_go::WorldCounters& c = world_->counters();
    return c.flight_steps + c.contact_searches + c.contact_search_steps + c.impacts +
           c.plane_contact_steps + c.plane_contact_rhs + c.nonsmooth_steps + c.nonsmooth_impulses +
           c.pair_searches + c.pair_search_steps + c.pair_gap_checks;
  }
  long events_reported() const override { return world_->counters().events; }
  std::vector<std::pair<std::string, long>> work_counters() const override {
    const virtual_go::WorldCounters& c = world_->counters();
    return {{"hold_failures", c.nonsmooth_hold_failures},
            {"joint_solves", c.nonsmooth_joint_solves},
            {"joint_iterations", c.nonsmooth_joint_iterations},
            {"joint_capped_solves", c.nonsmooth_joint_capped_solves}};
  }

 private:
  double nonsmooth_step_s_ = 0.0;  // 0: the default
  bool joint_solve_ = false;
  bool hold_check_ = true;
  std::optional<virtual_go::World> world_;
  std::vector<virtual_go::WorldEvent> events_;
  std::vector<Setting> settings_;
  double dt_ = 0.0;
  long k_ = 0;
};

}  // namespace

std::unique_ptr<ManyMethod> make_ours_many(double nonsmooth_step_s, bool joint_solve,
                                           bool hold_check) {
  return std::make_unique<OursMany>(nonsmooth_step_s, joint_solve, hold_check);
}

}  // namespace vg_bench
