#include "virtual_go/contact/simultaneous_impacts.h"

#include <string>

#include "virtual_go/common/validation.h"
#include "virtual_go/contact/pair_impact.h"
#include "virtual_go/contact/time_of_impact.h"

namespace virtual_go {

namespace {

// u_n of the contact: n . (u_B - u_A) at the contact point, < 0 approaching.
double normal_velocity(const std::vector<ImpactBody>& bodies, const BodyContact& c) {
  const ImpactBody& a = bodies[c.a];
  const ImpactBody& b = bodies[c.b];
  return c.normal_world.dot(point_velocity_world(b.model, b.state, c.point_world) -
                            point_velocity_world(a.model, a.state, c.point_world));
}

}  // namespace

SimultaneousImpacts resolve_simultaneous_impacts(std::vector<ImpactBody>& bodies,
                                                 const std::vector<BodyContact>& contacts,
                                                 const ContactMaterial& material,
                                                 const SimultaneousImpactOptions& options) {
  const int count = static_cast<int>(bodies.size());
  for (size_t k = 0; k < contacts.size(); ++k) {
    const BodyContact& c = contacts[k];
    if (c.a < 0 || c.a >= count || c.b < 0 || c.b >= count || c.a == c.b) {
      throw InvalidArgument("contacts", "contact " + std::to_string(k) + " joins bodies " +
                                            std::to_string(c.a) + " and " + std::to_string(c.b) +
                                            ": each must be one of the " + std::to_string(count) +
                                            " bodies, and they must differ");
    }
  }
  if (!(options.rest_speed_mps >= 0.0) || options.max_impacts < 0) {
    throw InvalidArgument("options", "rest_speed_mps must be >= 0 and max_impacts >= 0, got " +
                                         format_value(options.rest_speed_mps) + " and " +
                                         std::to_string(options.max_impacts));
  }
  validate_material("material", material);
  SimultaneousImpacts result;
  for (;;) {
    int fastest = -1;
    double fastest_un = -options.rest_speed_mps;
    for (size_t k = 0; k < contacts.size(); ++k) {
      const double un = normal_velocity(bodies, contacts[k]);
      if (un < fastest_un) {  // ties: the first listed
        fastest_un = un;
        fastest = static_cast<int>(k);
      }
    }
    result.largest_approach_mps = fastest < 0 ? 0.0 : -fastest_un;
    if (fastest < 0) {
      result.settled = true;
      return result;
    }
    if (result.impacts >= options.max_impacts) return result;
    const BodyContact& c = contacts[fastest];
    ImpactBody& a = bodies[c.a];
    ImpactBody& b = bodies[c.b];
    const PairImpact impact = resolve_pair_impact(a.model, a.state, b.model, b.state, c.point_world,
                                                  c.normal_world, material, options.impact);
    a.state = impact.state_a;
    b.state = impact.state_b;
    result.energy_change_j += impact.energy_change_j;
    ++result.impacts;
  }
}

}  // namespace virtual_go
