// The many-stone benchmark's shared types: a scene of several stones (black and white, each
// with its own shape and mass), the interface every method implements (ours and the peers),
// and the measures computed from what a method reports (energy, overlap).
//
// The stone, board, material, sample and setting types are the contact benchmark's
// (../contact/contact_method.h), so that a stone is given to every engine exactly as there.
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "../contact/contact_method.h"
#include "virtual_go/body/rigid_body_state.h"

namespace vg_bench {

enum class Colour { black, white };

struct ManyStone {
  Colour colour = Colour::black;
  virtual_go::RigidBodyState initial;  // angular momentum from omega_world
  Eigen::Vector3d omega_world = Eigen::Vector3d::Zero();
};

enum class SceneKind { rest, collision, cluster, drops };

struct ManyScene {
  std::string name;
  std::string description;
  SceneKind kind = SceneKind::rest;
  StoneSpec black;            // 22.2 mm slate, size 33
  StoneSpec white;            // 21.9 mm shell, size 33
  bool board_enabled = true;  // false: no board and no table (stones free in the air)
  BoardSpec board;
  // One law for every pair (stone-board, stone-table, stone-stone): the core has no separate
  // stone-stone material yet, and equal laws let Bullet's product rule give each pair its value.
  SurfaceMaterial material;
  Eigen::Vector3d gravity_world = Eigen::Vector3d(0.0, 0.0, -9.80665);
  std::vector<ManyStone> stones;
  double duration_s = 0.0;
  // The stones touch or will hit each other: a method without stone-stone contact cannot run it.
  bool needs_stone_contact = false;

  const StoneSpec& spec(std::size_t i) const {
    return stones[i].colour == Colour::black ? black : white;
  }
};

// Every method is driven on a fixed grid t_k = k dt, as in the contact benchmark:
//   reset(scene, dt)  builds the scene (not timed); throws ContactNotRun for what it cannot run
//   advance()         from t_k to t_(k+1) (timed; a peer takes one step of dt)
//   sample(i), asleep(i) the state of stone i at t_k and whether the method stopped moving it
class ManyMethod {
 public:
  virtual ~ManyMethod() = default;
  virtual std::string name() const = 0;  // "ours", "bullet", "ode", "mujoco"
  virtual bool is_peer() const { return true; }
  virtual bool has_sleep() const = 0;  // the engine can put bodies to sleep
  virtual void reset(const ManyScene& scene, double dt_s) = 0;
  virtual void advance() = 0;
  virtual ContactSample sample(std::size_t stone) const = 0;
  virtual bool asleep(std::size_t stone) const = 0;
  virtual std::string failure() const { return ""; }
  // Integration and search work since the reset (ours: the World's counters); -1: not known.
  virtual long work_done() const { return -1; }
  // Events the method reported since the reset (ours: impacts, contact changes, rests); -1: an
  // engine without events.
  virtual long events_reported() const { return -1; }
  // Named work counters since the reset, for the results file (ours: the joint solve's, when on).
  virtual std::vector<std::pair<std::string, long>> work_counters() const { return {}; }
  virtual std::vector<Setting> settings() const = 0;
  virtual std::string version() const = 0;
};

// nonsmooth_step_s > 0: ours with that island sub-step h (NonsmoothContactOptions::step_s)
// instead of the default (many_benchmark --nonsmooth-step, to measure what h does); joint_solve:
// with NonsmoothContactOptions::joint_solve on (many_benchmark --joint-solve; off by default);
// hold_check: NonsmoothContactOptions::hold_check (many_benchmark --no-hold-check turns it off).
std::unique_ptr<ManyMethod> make_ours_many(double nonsmooth_step_s = 0.0, bool joint_solve = false,
                                           bool hold_check = true);
std::unique_ptr<ManyMethod> make_bullet_many();
std::unique_ptr<ManyMethod> make_ode_many();
std::unique_ptr<ManyMethod> make_mujoco_many();
void init_many_peers();
void init_mujoco_many_messages();  // MuJoCo's warnings are read from mjData, not printed
void shutdown_many_peers();

// Scenes (many_scenes.cpp).
StoneSpec black_stone();
StoneSpec white_stone();
// The first n stones of the full board (row by row from A1, colours alternating as on a
// checkerboard), each flat on the board at rest, neighbours along a row touching.
ManyScene resting_board(int n, double duration_s);
// Two stones free in the air (no gravity, no board), flat, rims facing: `moving` (black) at
// speed along +x towards `target` (black or white) at rest, offset across by
// impact_parameter (m), first touch at 2.5 dt.
ManyScene two_stone_collision(Colour target, double speed_mps, double impact_parameter_m,
                              double dt_s);
// A black stone thrown into a 3 x 3 block of resting stones around the board's centre.
ManyScene thrown_into_cluster(double duration_s);
// n stones (row by row on a 19 x 19 grid of twice the Go pitch, on a board made large enough,
// so no two ever touch) dropped flat from staggered heights: each bounces on its own and comes
// to rest. Measures what an event costs as the number of stones grows.
ManyScene dropped_grid(int n, double duration_s);

// Measures (many_scenes.cpp).
// Total energy of stone i (J): 1/2 m v^2 + 1/2 w.I_world w - m g.x.
double stone_energy(const ManyScene& scene, std::size_t i, const ContactSample& s);
// How far two lenses overlap (m; <= 0: apart), as min over directions n of
// h_A(n) + h_B(-n) - n.(x_B - x_A) with the lenses' exact support functions, minimised over a
// grid of directions and then by a pattern search: every direction tried gives an upper bound
// of the true (translational) penetration depth, so the figure never understates an overlap.
double lens_overlap_m(const StoneSpec& a, const ContactSample& sa, const StoneSpec& b,
                      const ContactSample& sb);

}  // namespace vg_bench
