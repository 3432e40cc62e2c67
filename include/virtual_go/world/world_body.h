// A body the stones of a World refer to (docs/physics.md, "World"): its motion model (mass,
// inertia, the model's kind) and its lens, optionally the colour it stands for. Every stone
// refers to one body; stones of one colour share their colour's body, so a full board holds two
// bodies, not 361. The world's gravity, board and materials are the same for every body.
//
// WorldBodyModel is what the world makes of a body once: the motion setup with the world's
// gravity, the lens's contact geometry, its distance to the board, and the exact integrator
// that samples its flights.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>

#include "virtual_go/body/motion_model.h"
#include "virtual_go/flight/integrator.h"
#include "virtual_go/geometry/lens_geometry.h"
#include "virtual_go/geometry/lens_shape.h"
#include "virtual_go/go/board_distance.h"
#include "virtual_go/go/stone_color.h"
#include "virtual_go/go/stone_set.h"

namespace virtual_go {

struct WorldBody {
  MotionModel model;
  LensShape shape;
  std::optional<StoneColor> color;  // none: a body of the WorldConfig (the single-stone node)
};

// A set's body of one colour moved by a motion model of `kind`.
WorldBody world_body(const StoneBody& body, MotionModelKind kind);

class WorldBodyModel {
 public:
  // Throws InvalidArgument naming the field ("body/inertia": an inertia without a closed-form
  // flight, "gravity").
  WorldBodyModel(const WorldBody& body, const Eigen::Vector3d& gravity_world,
                 const BoardGeometry& board);

  const WorldBody& body() const { return body_; }
  const MotionSetup& setup() const { return setup_; }
  const LensGeometry& lens() const { return lens_; }
  const BoardDistance& board() const { return board_; }
  const Integrator& exact() const { return *exact_; }

 private:
  WorldBody body_;
  MotionSetup setup_;
  LensGeometry lens_;
  BoardDistance board_;
  std::shared_ptr<const Integrator> exact_;  // stateless: copies of the model may share it
};

// The fastest any surface point of a lens with kinetic energy kinetic_j (J) can move (m/s): every
// surface point lies within the rim radius a of the centre, so |u| <= |v| + a |omega|, and with
// m v^2 + I_min omega^2 <= 2 K, Cauchy-Schwarz gives the largest such sum:
// |v| + a |omega| <= sqrt(2 K (1/m + a^2/I_min)) (the two maxima added: 1.32x that).
double point_speed_from_energy(const MotionModel& model, const LensGeometry& lens,
                               double kinetic_j);

}  // namespace virtual_go
