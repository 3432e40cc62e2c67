// The default stone (size 33 slate, 22 mm) as a motion setup: the body most core tests fly.
#pragma once

#include <Eigen/Core>

#include "virtual_go/body/rigid_body.h"
#include "virtual_go/flight/integrator.h"
#include "virtual_go/go/stone.h"

namespace vgtest {

inline virtual_go::MotionSetup stone_setup(
    virtual_go::MotionModelKind kind = virtual_go::MotionModelKind::rigid_body,
    const Eigen::Vector3d& gravity_world = virtual_go::kStandardGravity) {
  return {virtual_go::MotionModel(kind,
                                  virtual_go::make_stone(virtual_go::StoneSpec{}).mass_properties),
          gravity_world};
}

}  // namespace vgtest
