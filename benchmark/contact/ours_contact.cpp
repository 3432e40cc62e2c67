// Ours: the virtual_go core's event-driven contact (virtual_go::World: exact flight between
// exact times of impact, Stronge impacts, sustained contact in constraint coordinates, exact
// rest; docs/physics.md, "World"), behind the same interface as the peers. The world is sampled
// on the grid as the node samples it: advance_to(k dt) goes through every event up to k dt, and
// the state read afterwards is the exact state at k dt.
#include <cmath>
#include <optional>

#include "contact_method.h"
#include "settings_format.h"
#include "virtual_go/world/world.h"

namespace vg_bench {
namespace {

virtual_go::ContactMaterial to_core(const SurfaceMaterial& m) {
  virtual_go::ContactMaterial c;
  c.restitution = m.restitution;
  c.friction = m.friction;
  c.rolling_resistance_m = m.rolling_resistance_m;
  c.spinning_friction_m = m.spinning_friction_m;
  return c;
}

std::string material_text(const virtual_go::ContactMaterial& m) {
  return "e* " + num(m.restitution) + ", mu " + num(m.friction) + ", l_r " +
         num(m.rolling_resistance_m) + " m, l_s " + num(m.spinning_friction_m) + " m";
}

// Everything the world integrates or searches; none of it may grow while the stone rests.
long work_of(const virtual_go::WorldCounters& c) {
  return c.flight_steps + c.contact_searches + c.contact_search_steps + c.impacts +
         c.plane_contact_steps + c.plane_contact_rhs + c.nonsmooth_steps + c.nonsmooth_impulses;
}

class OursContact : public ContactMethod {
 public:
  std::string name() const override { return "ours"; }
  std::string family() const override { return "ours"; }
  std::string variant() const override { return "events"; }
  bool is_peer() const override { return false; }
  std::string version() const override { return "virtual_go core (this tree)"; }

  void reset(const ContactScenario& s, double dt) override {
    // The world has no option that holds the rotation; as the core's own frozen-slide test
    // (test/contact/test_plane_contact.cpp) does, the stone gets moments of inertia of
    // 10^6 kg m^2: friction's couple (mu m g c ~ 7e-5 N m) then turns it by ~1e-11 rad in the
    // slide, far below every figure measured. Isotropic, so the flight stays in closed form.
    const Eigen::Vector3d moments = s.rotation_frozen ? Eigen::Vector3d::Constant(kFrozenMoment)
                                                      : s.stone.principal_moments_body;
    frozen_ = s.rotation_frozen;
    const virtual_go::MotionModel model(virtual_go::MotionModelKind::rigid_body,
                                        virtual_go::MassProperties(s.stone.mass_kg, moments));
    virtual_go::WorldConfig config(
        virtual_go::MotionSetup{model, s.gravity_world},
        virtual_go::LensShape(2.0 * s.stone.half_width_m, 2.0 * s.stone.half_height_m));
    config.board.size_x_m = s.board.size_x_m;
    config.board.size_y_m = s.board.size_y_m;
    config.board.thickness_m = s.board.thickness_m;
    config.board_material = to_core(s.board_material);
    config.table_material = to_core(s.table_material);
    config.zeno_height_m = 1e-6;
    world_.reset();
    world_.emplace(config, s.initial, 0.0);
    dt_ = dt;
    k_ = 0;
    events_.clear();
    event_count_ = 0;
    impact_count_ = 0;
    work_at_sleep_ = -1;
    rest_time_s_ = NAN;
  }

  void advance() override {
    ++k_;
    events_.clear();
    world_->advance_to(static_cast<double>(k_) * dt_, events_);
    event_count_ += static_cast<long>(events_.size());
    for (const virtual_go::WorldEvent& e : events_) {
      if (e.kind == virtual_go::WorldEventKind::impact) ++impact_count_;
      if (e.kind == virtual_go::WorldEventKind::rest && std::isnan(rest_time_s_))
        rest_time_s_ = e.time_s;
    }
    if (world_->is_resting(0)) {
      if (work_at_sleep_ < 0) work_at_sleep_ = work_of(world_->counters());
    } else {
      work_at_sleep_ = -1;  // woken (never, in these scenarios): counted from the next rest
    }
  }

  ContactSample sample() const override {
    const virtual_go::RigidBodyState& st = world_->state(0);
    ContactSample smp;
    smp.position_world = st.position_world;
    smp.orientation = st.orientation;
    smp.velocity_world = st.velocity_world;
    smp.omega_world =
        world_->setup().model.angular_velocity_world(st.orientation, st.angular_momentum_world);
    return smp;
  }

  bool asleep() const override { return world_->is_resting(0); }

  ContactCounters counters() const override {
    const virtual_go::WorldCounters& w = world_->counters();
    ContactCounters c;
    c.events = event_count_;
    c.impacts = impact_count_;
    c.rhs_evaluations = w.plane_contact_rhs;
    c.contact_steps = w.plane_contact_steps;
    c.fallback_steps = w.nonsmooth_steps;
    c.work_while_asleep = work_at_sleep_ < 0 ? -1 : work_of(w) - work_at_sleep_;
    c.rest_event_time_s = rest_time_s_;
    return c;
  }

  std::vector<Setting> settings() const override {
    if (!world_) return {{"contact law", "not built yet", ""}};
    const virtual_go::WorldConfig& c = world_->config();
    const virtual_go::WorldOptions& o = c.options;
    const std::string phys = "docs/physics.md, ";
    return {
        {"contact law",
         "exact flight, exact time of impact, Stronge impact, sustained plane contact in "
         "constraint coordinates, exact rest; nonsmooth fallback on edges and sides",
         phys + "\"World\""},
        {"stone inertia",
         frozen_ ? "rotation frozen: moments " + num(kFrozenMoment) +
                       " kg m^2 (as the core's frozen-slide test)"
                 : "the stone's (I1, I1, I3)",
         "benchmark/contact/ours_contact.cpp"},
        {"board material", material_text(c.board_material), phys + "\"Contact materials\""},
        {"table material", material_text(c.table_material), phys + "\"Contact materials\""},
        {"Zeno height (m)", num(c.zeno_height_m), phys + "\"Impact\""},
        {"time of impact: touch / polish tolerance (m)",
         num(o.time_of_impact.touch_tolerance_m) + " / " + num(o.time_of_impact.polish_gap_m),
         phys + "\"Time of impact\""},
        {"plane contact: rel. / abs. tolerance, max step (s), event resolution (s)",
         num(o.plane_contact.relative_tolerance) + " / " + num(o.plane_contact.absolute_tolerance) +
             ", " + num(o.plane_contact.max_step_s) + ", " +
             num(o.plane_contact.event_resolution_s),
         phys + "\"Sustained contact\" (Dormand-Prince 8(5,3), dop853.h)"},
        {"fallback: sub-step (s), rest speed (m/s) for (s)",
         num(o.nonsmooth.step_s) + ", " + num(o.nonsmooth.rest_speed_mps) + " for " +
             num(o.nonsmooth.rest_time_s),
         phys + "\"World\" (the fallback)"},
        {"sampling", "advance_to(k dt): every event up to k dt, the exact state at k dt",
         phys + "\"World\""},
    };
  }

 private:
  std::optional<virtual_go::World> world_;
  std::vector<virtual_go::WorldEvent> events_;
  double dt_ = 0.0;
  long k_ = 0;
  long event_count_ = 0, impact_count_ = 0;
  static constexpr double kFrozenMoment = 1e6;  // kg m^2, for rotation_frozen
  bool frozen_ = false;
  long work_at_sleep_ = -1;   // the world's work when the stone fell asleep; -1: awake
  double rest_time_s_ = NAN;  // the first rest event's time
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
