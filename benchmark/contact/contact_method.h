// The contact benchmark's shared types: a scenario (stone, board, table, materials, initial
// state, closed-form references), the state a method reports at a grid time, and the interface
// every method implements (ours and the peer engines alike).
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "virtual_go/body/rigid_body_state.h"

namespace vg_bench {

// One surface pair's contact law, field for field the core's virtual_go::ContactMaterial.
struct SurfaceMaterial {
  double restitution = 0.5;            // Stronge's energetic e* in [0, 1]
  double friction = 0.3;               // Coulomb mu
  double rolling_resistance_m = 5e-6;  // l_r, m: rolling couple <= l_r N
  double spinning_friction_m = 15e-6;  // l_s, m: spinning couple <= l_s N
};

// The board as a box whose top face is at z = 0, centred on the origin, on a table plane at
// z = -thickness (the core's virtual_go::BoardGeometry, sizes only).
struct BoardSpec {
  double size_x_m = 0.4242;
  double size_y_m = 0.4545;
  double thickness_m = 0.1515;
  double top_z_m() const { return 0.0; }
  double table_z_m() const { return -thickness_m; }
  Eigen::Vector3d half_extent_m() const {
    return {0.5 * size_x_m, 0.5 * size_y_m, 0.5 * thickness_m};
  }
  Eigen::Vector3d centre_world() const { return {0.0, 0.0, -0.5 * thickness_m}; }
};

// The stone: a biconvex lens of half-width a and half-height c, body z the symmetry axis.
struct StoneSpec {
  double half_width_m = 0.0;   // a
  double half_height_m = 0.0;  // c
  double mass_kg = 0.0;
  Eigen::Vector3d principal_moments_body = Eigen::Vector3d::Zero();  // (I1, I1, I3), kg m^2
  double sphere_radius_m() const;                                    // R = (a^2 + c^2) / 2c
  double sphere_offset_m() const;                                    // d = R - c
  // Lowest point of the lens in the world (the exact support in direction -z).
  Eigen::Vector3d lowest_point_world(const Eigen::Vector3d& centre_world,
                                     const Eigen::Quaterniond& orientation) const;
};

// A flat drop: the stone's lowest point starts h0 above the board, restitution e. Closed form
// for a flat landing on the pole: apex heights e^(2n) h0; impacts at t_1 = sqrt(2 h0 / g) and
// t_(n+1) = t_n + 2 e^n t_1; rest at sqrt(2 h0 / g) (1 + e) / (1 - e) (the Zeno limit).
struct FlatDropReference {
  double height_m = 0.0;     // h0, lowest point above the board top
  double restitution = 0.0;  // e
  double gravity = 0.0;      // |g|, m/s^2
  double fall_time_s() const;
  double apex_height_m(int bounce) const;  // bounce n >= 0 (0: the release height)
  double impact_time_s(int impact) const;  // impact n >= 1
  double rest_time_s() const;              // Zeno limit of the impact times
  // Impact at which the rebound height falls below h_min (the core's Zeno cut-off, 1 um):
  // the stone is at rest from there on, slightly before rest_time_s().
  int last_bounce_above(double h_min_m) const;
  double rest_time_with_cutoff_s(double h_min_m) const;
  // Height of the lowest point above the board at time t and its rate (piecewise parabolas;
  // 0 after the impact whose rebound would be lower than 1 um).
  double height_at(double t) const;
  double velocity_at(double t) const;
};

// Sliding flat at v0 with friction mu: with rotation frozen s = v0^2 / (2 mu g) in
// t = v0 / (mu g); a free lens pitches forward and slips a little less far.
struct SlideReference {
  double speed_mps = 0.0;
  double friction = 0.0;
  double gravity = 0.0;
  double frozen_distance_m() const;
  double frozen_stop_time_s() const;
  // A free lens pitches forward (friction acts c below the centre): the centre's displacement
  // and the time when the contact point stops slipping, and the largest pitch, integrated by
  // integrate_free_lens() from the pitch-plane equations (no closed form).
  double free_distance_m = NAN;
  double free_slip_end_s = NAN;
  double free_max_pitch_rad = NAN;
  void integrate_free_lens(const StoneSpec& stone);
};

struct ContactScenario {
  std::string name;
  std::string description;
  StoneSpec stone;
  BoardSpec board;
  SurfaceMaterial board_material;  // stone on the board
  SurfaceMaterial table_material;  // stone on the table
  Eigen::Vector3d gravity_world = Eigen::Vector3d(0.0, 0.0, -9.80665);
  virtual_go::RigidBodyState initial;  // angular momentum from initial_omega_world
  Eigen::Vector3d initial_omega_world = Eigen::Vector3d::Zero();
  double duration_s = 0.0;
  bool rotation_frozen = false;  // the stone may only translate (a test of the friction law)
  std::optional<FlatDropReference> drop;
  std::optional<SlideReference> slide;
};

// The state a method reports at a grid time, in our conventions (q body -> world).
struct ContactSample {
  Eigen::Vector3d position_world = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d velocity_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d omega_world = Eigen::Vector3d::Zero();
};

// Work counters since the last reset; -1 where a method has no such notion.
struct ContactCounters {
  long events = -1;           // ours: events handled (impacts, mode changes, rest, wake)
  long impacts = -1;          // ours: impacts among them
  long rhs_evaluations = -1;  // ours: right-hand-side evaluations of sustained contact
  long contact_steps = -1;    // ours: accepted integrator steps of sustained contact
  long fallback_steps = -1;   // ours: sub-steps of the nonsmooth fallback
  // ours: integration and search work done since the stone last fell asleep (flight steps,
  // searches, impacts, contact steps and evaluations, fallback sub-steps); -1 while awake.
  long work_while_asleep = -1;
  double rest_event_time_s = NAN;  // ours: the time of the first rest event (exact, off the grid)
};

// One setting as run, for the settings tables (defaults vs tuned) of docs/benchmarks/.
struct Setting {
  std::string name;
  std::string value;
  std::string documentation;  // where the engine's documentation describes it
};

// A method refuses a configuration it cannot run; the reason goes into the tables.
class ContactNotRun : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Every method, ours and the peers, is driven the same way on a fixed grid t_k = k dt:
//   reset(scenario, dt)   builds the scene and puts the stone in its initial state (k = 0);
//                         not timed; throws ContactNotRun for what it cannot run
//   advance()             from t_k to t_(k+1) (timed; a peer takes one step of dt)
//   sample(), asleep()    the state at t_k and whether the method stopped integrating it
//   counters()            work since the reset (events for ours)
class ContactMethod {
 public:
  virtual ~ContactMethod() = default;
  virtual std::string name() const = 0;     // unique, e.g. "bullet_tuned"
  virtual std::string family() const = 0;   // "ours", "bullet", "ode", "mujoco"
  virtual std::string variant() const = 0;  // "defaults", "tuned", "events"
  virtual bool is_peer() const { return true; }
  virtual void reset(const ContactScenario& scenario, double dt_s) = 0;
  virtual void advance() = 0;
  virtual ContactSample sample() const = 0;
  virtual bool asleep() const = 0;
  virtual ContactCounters counters() const { return {}; }
  // Non-empty when the engine flagged the run as failed although the state looks finite.
  virtual std::string failure() const { return ""; }
  // The settings of the last reset, read back from the engine where it can tell.
  virtual std::vector<Setting> settings() const = 0;
  // Engine name and version, for the notes.
  virtual std::string version() const = 0;
};

// The lens tessellation every peer is given (the same vertices for all of them; the poles and
// the rim are exact surface points, so a flat stone rests on the pole at exactly z = c).
constexpr int kHullSegments = 32;  // around the rim
constexpr int kHullRings = 4;      // from the rim to each pole
struct LensHull {
  std::vector<Eigen::Vector3d> vertices_body;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside
};
LensHull make_lens_hull(const StoneSpec& stone);

std::unique_ptr<ContactMethod> make_ours_contact();
// The flat drop's closed form sampled on the grid, behind the same interface: what an exact
// method reports. Only for --self-check (the metrics must find it exact); refuses the other
// scenarios.
std::unique_ptr<ContactMethod> make_closed_form_drop();
std::unique_ptr<ContactMethod> make_bullet_contact(bool tuned);
std::unique_ptr<ContactMethod> make_ode_contact(bool tuned);
std::unique_ptr<ContactMethod> make_mujoco_contact(bool tuned);
void init_contact_peers();
void init_mujoco_messages();  // MuJoCo's warnings are read from mjData, not printed
void shutdown_contact_peers();

std::vector<ContactScenario> make_contact_scenarios();

}  // namespace vg_bench
