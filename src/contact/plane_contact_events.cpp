// PlaneContact's event functions (plane_contact_laws.h): each is positive while the mode holds
// and crosses zero where the mode must change.
#include <cmath>

#include "plane_contact_laws.h"

namespace virtual_go::plane_contact_detail {
namespace {

// Positive while the speed stays on the part's side of its direction layer's edge.
double layer_margin(const ContactLawPart& part, double speed, double layer_speed) {
  return part.layer == ContactLawPart::Layer::inside ? layer_speed - speed : speed - layer_speed;
}

}  // namespace

double PlaneContactLaws::event_value(Trigger trigger, const PlaneContactKinematics& k,
                                     const PlaneContactMode& mode,
                                     const PlaneContactForces* forces) const {
  const double cos_beta = setup_.lens.cos_cap_cone();
  const ContactMaterial& law = setup_.material;
  switch (trigger) {
    case Trigger::part_switch:
      switch (mode.part) {
        case LensPart::bottom_cap:
          return k.axis_world.z() - cos_beta;
        case LensPart::top_cap:
          return -k.axis_world.z() - cos_beta;
        case LensPart::rim:
        default:
          return cos_beta - std::abs(k.axis_world.z());
      }
    case Trigger::region:
      return region_.margin_m((k.position_world + k.offset_world).head<2>());
    case Trigger::clearance:
      return options_.clearance_m(LensPose{k.position_world, k.axis_world});
    case Trigger::tangential_zero:
      return k.slip_velocity().dot(mode.tangential.reference_world);
    case Trigger::rolling_zero:
      return k.rolling_velocity().dot(mode.rolling.reference_world);
    case Trigger::spinning_zero:
      return k.spin_velocity() * mode.spinning.reference_world.z();
    case Trigger::tangential_layer:
      return layer_margin(mode.tangential, k.slip_velocity().norm(), kSlipDirectionLayer);
    case Trigger::rolling_layer:
      return layer_margin(mode.rolling, k.rolling_velocity().norm(), kRollDirectionLayer);
    default:
      break;
  }
  const PlaneContactForces f = forces ? *forces : solve(slaved(mode, k), k);
  switch (trigger) {
    case Trigger::lift_off:
      return f.normal_force_n;
    case Trigger::tangential_bound:
      return law.friction * f.normal_force_n - f.friction_force_world.norm();
    case Trigger::rolling_bound:
      return law.rolling_resistance_m * f.normal_force_n - f.rolling_couple_world.norm();
    case Trigger::spinning_bound:
      return law.spinning_friction_m * f.normal_force_n - std::abs(f.spinning_couple_nm);
    default:
      return 0.0;
  }
}

EventValues PlaneContactLaws::event_values(const PlaneContactKinematics& k,
                                           const PlaneContactMode& mode,
                                           const PlaneContactForces* forces,
                                           bool skip_clearance) const {
  // Which events the mode can meet: a sliding part can stop, a stuck part can start.
  EventValues e;
  auto activate = [&](Trigger t) { e.active[static_cast<int>(t)] = true; };
  activate(Trigger::part_switch);
  activate(Trigger::lift_off);
  if (region_.kind != PlaneRegion::Kind::whole_plane) activate(Trigger::region);
  if (options_.clearance_m) activate(Trigger::clearance);
  const std::pair<ContactLaw, std::pair<Trigger, Trigger>> parts[] = {
      {mode.tangential.law, {Trigger::tangential_zero, Trigger::tangential_bound}},
      {mode.rolling.law, {Trigger::rolling_zero, Trigger::rolling_bound}},
      {mode.spinning.law, {Trigger::spinning_zero, Trigger::spinning_bound}}};
  for (const auto& [law, triggers] : parts) {
    if (law == ContactLaw::sliding) activate(triggers.first);
    if (law == ContactLaw::stuck) activate(triggers.second);
  }
  auto layered = [](const ContactLawPart& p) {
    return p.law == ContactLaw::sliding && p.layer != ContactLawPart::Layer::by_speed;
  };
  if (layered(mode.tangential)) activate(Trigger::tangential_layer);
  if (layered(mode.rolling)) activate(Trigger::rolling_layer);
  PlaneContactForces solved;
  if (!forces) {
    ++counters_.extra_solves;
    solved = solve(slaved(mode, k), k);
    forces = &solved;
  }
  for (int i = 0; i < kTriggerCount; ++i) {
    if (!e.active[i] || (skip_clearance && static_cast<Trigger>(i) == Trigger::clearance)) continue;
    e.g[i] = event_value(static_cast<Trigger>(i), k, mode, forces);
  }
  return e;
}

}  // namespace virtual_go::plane_contact_detail
