// Several stones touching at once and colliding at the same instant (a row struck at one end, a
// stone landing across two neighbours): a documented rule that never adds energy (docs/physics.md,
// "Stone–stone contact (primitives)").
//
// The rule: resolve the contact that approaches fastest with the two-body impact
// (pair_impact.h), update both stones, and repeat until no contact approaches faster than
// `rest_speed_mps`. Each two-body impact has dE <= 0, so the sequence has dE <= 0, and momentum
// and angular momentum are conserved at every step. For a row of equal stones, frictionless and
// elastic, this is the textbook Newton's cradle (one stone in, one stone out); with e* < 1 it is
// the cradle whose stones hang with vanishing gaps (each impact completes before the next), the
// model in which the classical cradle analysis is exact. A simultaneous solve over all contacts
// (one complementarity problem, as time-stepping engines do) does not in general reproduce the
// cradle; the order of impacts matters, and this rule fixes it (fastest approach first, ties by
// the order of `contacts`).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "virtual_go/body/motion_model.h"
#include "virtual_go/body/rigid_body_state.h"
#include "virtual_go/contact/impact.h"
#include "virtual_go/contact/material.h"

namespace virtual_go {

struct ImpactBody {
  const MotionModel& model;
  RigidBodyState state;  // updated in place
};

// A contact between bodies[a] and bodies[b] at point_world with the unit normal from a to b.
struct BodyContact {
  int a = 0, b = 0;
  Eigen::Vector3d point_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal_world = Eigen::Vector3d::UnitX();
};

struct SimultaneousImpactOptions {
  double rest_speed_mps = 1e-12;  // a contact approaching slower than this is done
  int max_impacts = 100000;       // then stop and say so (`settled` false)
  ImpactOptions impact;           // for each two-body impact
};

struct SimultaneousImpacts {
  int impacts = 0;                    // two-body impacts applied
  double energy_change_j = 0.0;       // sum of their dE, each <= 0
  double largest_approach_mps = 0.0;  // fastest approach left at the end (<= rest speed if settled)
  bool settled = false;
};

// Applies the rule to `bodies` through `contacts` with one material for all contacts. Throws
// InvalidArgument for an index out of range or a contact of a body with itself (field
// "contacts"), and as resolve_pair_impact does.
SimultaneousImpacts resolve_simultaneous_impacts(std::vector<ImpactBody>& bodies,
                                                 const std::vector<BodyContact>& contacts,
                                                 const ContactMaterial& material,
                                                 const SimultaneousImpactOptions& options = {});

}  // namespace virtual_go
