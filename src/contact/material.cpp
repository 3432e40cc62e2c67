#include "virtual_go/contact/material.h"

#include <cmath>

#include "virtual_go/common/validation.h"

namespace virtual_go {
namespace {

// Largest length of a rolling or spinning couple arm: far beyond a stone's size (11 mm), small
// enough that no product with a force overflows.
constexpr double kMaxCoupleLengthM = 1.0;
// Far above any real surface pair. Note that a sliding lens can meet Painleve's paradox (no
// consistent contact force) above mu ~ 0.99 (found at mu >= 0.986 over 2e5 random orientations
// of a size-33 stone); impacts are fine for any mu, so the node bounds its parameter instead.
constexpr double kMaxFriction = 100.0;

void require_range(const std::string& field, double value, double lo, double hi, const char* unit) {
  if (!(value >= lo && value <= hi)) {  // also refuses NaN
    throw InvalidArgument(field, field + " must be between " + format_value(lo) + " and " +
                                     format_value(hi) + unit + ", got " + format_value(value));
  }
}

}  // namespace

void validate_material(const std::string& field, const ContactMaterial& m) {
  // Every impulse of the nonsmooth fallback validates its material: the field names (four
  // string concatenations) are built only when a value is out of range.
  auto within = [](double value, double lo, double hi) { return value >= lo && value <= hi; };
  if (within(m.restitution, 0.0, 1.0) && within(m.friction, 0.0, kMaxFriction) &&
      within(m.rolling_resistance_m, 0.0, kMaxCoupleLengthM) &&
      within(m.spinning_friction_m, 0.0, kMaxCoupleLengthM)) {
    return;
  }
  require_range(field + "/restitution", m.restitution, 0.0, 1.0, "");
  require_range(field + "/friction", m.friction, 0.0, kMaxFriction, "");
  require_range(field + "/rolling_resistance", m.rolling_resistance_m, 0.0, kMaxCoupleLengthM,
                " m");
  require_range(field + "/spinning_friction", m.spinning_friction_m, 0.0, kMaxCoupleLengthM, " m");
}

}  // namespace virtual_go
