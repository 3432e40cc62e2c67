// The impulse maths of the island's plastic sweeps (nonsmooth_island_sub_step.cpp, step 3): a
// contact's compliance, the friction of a contact that no longer approaches but slips, and a
// per-sub-step store of the compliances. Within one sub-step's sweeps the impulses change
// velocities and angular momenta, and poses only by the impacts' renormalised orientations (last
// bits), so a member's inverse world inertia and a contact's compliance are computed once per pose,
// with the arithmetic of a fresh computation (the sweeps' results are the same bit for bit).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <utility>
#include <vector>

#include "virtual_go/body/motion_model.h"
#include "virtual_go/body/rigid_body_state.h"

namespace virtual_go {

// The compliance K of a contact (its velocity changes by K P for an impulse P at the point):
// m^-1 1 - [r] I_world^-1 [r], r from the centre of mass to the point (m), 1/kg.
Eigen::Matrix3d contact_compliance(double mass_kg, const Eigen::Matrix3d& inverse_inertia_world,
                                   const Eigen::Vector3d& lever_arm_world);

// Whether friction_impulse can act at a contact of unit normal n whose velocity is u (m/s) and
// whose impulses so far in the sub-step sum to `accumulated` (N s): mu > 0, a positive normal
// impulse, and a slip speed above slip_tolerance_mps. Cheap: asked before K is needed.
bool may_slip(const Eigen::Vector3d& n, const Eigen::Vector3d& u,
              const Eigen::Vector3d& accumulated, double mu, double slip_tolerance_mps);

// Friction at a contact that no longer approaches but still slips (u_t), after earlier impulses
// of the sub-step pressed it with the normal impulse N (accumulated: the contact's impulses so
// far, normal n, compliance k): the tangential impulse alpha P_t, P_t = -K_tt^-1 u_t the one that
// stops the slip, alpha in [0, 1] the largest that keeps the contact's total tangential impulse
// within mu N. Its energy change is (alpha^2 / 2 - alpha) u_t K_tt^-1 u_t <= 0. Zero when nothing
// to do (may_slip false, or the cone already full).
Eigen::Vector3d friction_impulse(const Eigen::Vector3d& n, const Eigen::Matrix3d& k,
                                 const Eigen::Vector3d& u, const Eigen::Vector3d& accumulated,
                                 double mu, double slip_tolerance_mps);

// One sub-step's compliances: of each member's board and table contacts (slots 2 i, 2 i + 1) and
// of each pair contact (K_a + K_b), and each member's inverse world inertia behind them, for the
// contact points of the sub-step's gather. Made after the impacts between members (which hand
// back validated states, their orientation renormalised): the sweeps change velocities only, so
// each member's entry, made at its first use, holds for the whole sweep stage (asserted where
// assertions are compiled in; the package builds with NDEBUG).
class SweepCompliances {
 public:
  SweepCompliances() = default;
  SweepCompliances(std::size_t members, std::size_t pairs) { reset(members, pairs); }
  // Empty entries for a new sub-step, in the storage already held (no allocation once grown).
  void reset(std::size_t members, std::size_t pairs);
  // Member i's contact in slot k (0, 1) at point_world.
  const Eigen::Matrix3d& board(std::size_t i, int k, const MotionModel& model,
                               const RigidBodyState& s, const Eigen::Vector3d& point_world);
  // Member i's own compliance at point_world (not kept: a held stone's contact, seldom asked).
  Eigen::Matrix3d member_at(std::size_t i, const MotionModel& model, const RigidBodyState& s,
                            const Eigen::Vector3d& point_world);
  // The velocity of member i's material point at point_world: v + (I_world^-1 L) x r, with the
  // kept inverse inertia (the poses stay through the sweeps: no rotation of L per call).
  Eigen::Vector3d point_velocity(std::size_t i, const MotionModel& model, const RigidBodyState& s,
                                 const Eigen::Vector3d& point_world);
  // Pair contact j between members a (model_a, s_a) and b at point_world: K_a + K_b.
  const Eigen::Matrix3d& pair(std::size_t j, std::size_t a, const MotionModel& model_a,
                              const RigidBodyState& s_a, std::size_t b, const MotionModel& model_b,
                              const RigidBodyState& s_b, const Eigen::Vector3d& point_world);

 private:
  struct MemberEntry {
    bool ready = false;
    Eigen::Vector3d position_world;  // the compliances' lever arms start here
    Eigen::Matrix3d inverse_inertia_world;
  };
  struct ContactEntry {
    bool ready = false;
    Eigen::Matrix3d k;
  };
  // Member i's entry (made at the first call of the sub-step).
  const MemberEntry& member(std::size_t i, const MotionModel& model, const RigidBodyState& s);
  Eigen::Matrix3d compliance(const MemberEntry& m, const MotionModel& model,
                             const Eigen::Vector3d& point_world) const;
  std::vector<MemberEntry> members_;
  std::vector<ContactEntry> board_, pair_;
};

// Which contacts of one sub-step's velocity sweeps need no new look: a contact's check depends
// only on its members' velocities and on its own impulses of the sub-step, so one that found
// nothing to do finds nothing again until an impulse changes one of its members. The sweeps then
// skip it: the same impulses in the same order, bit for bit, without re-evaluating the contacts
// of members the sweep no longer moves. Contacts: board slots 2 i + k and pair indices j (an
// obstacle pair has one member).
class SweepSettled {
 public:
  SweepSettled() = default;
  SweepSettled(std::size_t members, std::size_t pairs) { reset(members, pairs); }
  // Nothing settled, for a new sub-step, in the storage already held.
  void reset(std::size_t members, std::size_t pairs) {
    version_.assign(members, 0);
    board_.assign(2 * members, -1);
    pair_.assign(pairs, {-1, -1});
  }
  // An impulse changed member i's velocities.
  void changed(std::size_t i) { ++version_[i]; }
  bool board(std::size_t slot, std::size_t i) const { return board_[slot] == version_[i]; }
  void board_idle(std::size_t slot, std::size_t i) { board_[slot] = version_[i]; }
  bool pair(std::size_t j, std::size_t a, std::size_t b) const {
    return pair_[j].first == version_[a] && pair_[j].second == version_[b];
  }
  void pair_idle(std::size_t j, std::size_t a, std::size_t b) {
    pair_[j] = {version_[a], version_[b]};
  }
  bool obstacle(std::size_t j, std::size_t a) const { return pair_[j].first == version_[a]; }
  void obstacle_idle(std::size_t j, std::size_t a) { pair_[j].first = version_[a]; }

 private:
  std::vector<long> version_;                // per member: impulses applied so far
  std::vector<long> board_;                  // per board slot: its member's version when idle
  std::vector<std::pair<long, long>> pair_;  // per pair: its members' versions when idle
};

}  // namespace virtual_go
