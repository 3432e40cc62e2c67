// ODE: the stone as a dConvex geom of the tessellated lens on a body, the board a static dBox,
// the table a dPlane; collisions through dSpaceCollide, contact joints from dCollide (at most
// 8 per geom pair), dWorldStep (ODE's exact big-matrix LCP step), one step per grid interval.
//
// Defaults: ODE's world defaults (ERP, CFM, no surface layer, no limit on the correcting
// velocity, auto-disable off) and a contact surface with only what the scenario asks for, as
// the ODE manual describes the dSurfaceParameters: mode dContactBounce, bounce e,
// bounce_vel 0 (the struct's zero; no default exists), mu = the scenario's mu. Without
// dContactApprox1 ODE reads mu as a constant friction-force limit in newtons, not a
// coefficient (ODE manual, "Contact"), which is what a user gets who sets mu = 0.3.
// Tuned for a 22 mm body (ODE manual: "Contact", "World", "Automatic Enabling and
// Disabling"): Coulomb friction proportional to the normal force (dContactApprox1) with
// rolling and spinning friction (dContactRolling, rho = l_r, rhoN = l_s), bounce_vel 4.4 mm/s
// (the speed of a 1 um rebound; Bullet's 0.2 m/s scaled by 0.022 is the same), the surface
// layer scaled to the body (0.001 m x 0.022), auto-disable on with the linear threshold scaled
// and an idle time of 0.1 s (so that the turning points of a rocking stone do not count as
// rest). The largest correcting velocity stays unlimited: limited to a few mm/s, a stone that
// sank one step deep at 60 Hz stays in the box and falls through it.
#include <ode/ode.h>

#include <csetjmp>
#include <cstdarg>
#include <cstdio>
#include <memory>

#include "contact_method.h"
#include "settings_format.h"

namespace vg_bench {
namespace {

constexpr double kScale = 0.022;
constexpr int kMaxContacts = 8;

// ODE's internal checks call the error or debug handler and abort() when it returns. A run
// that trips one is reported as failed: the handler jumps back into OdeContact::advance()
// (no C++ exception may unwind through ODE's step: its destructors assert again), and the
// world it left half-stepped is abandoned, not destroyed.
std::jmp_buf* g_ode_jump = nullptr;
bool g_ode_abandoned = false;  // then ODE's global state is not torn down either
char g_ode_error[512] = "";
void ode_fatal(int errnum, const char* msg, va_list ap) {
  char text[400];
  std::vsnprintf(text, sizeof text, msg, ap);
  std::snprintf(g_ode_error, sizeof g_ode_error, "ODE internal error %d: %s", errnum, text);
  if (g_ode_jump) std::longjmp(*g_ode_jump, 1);
  std::fprintf(stderr, "%s\n", g_ode_error);
  std::abort();
}
// ODE's messages (e.g. "LCP internal error, s <= 0") are counted, not printed.
long g_ode_messages = 0;
void ode_message(int, const char*, va_list) { ++g_ode_messages; }

class OdeContact : public ContactMethod {
 public:
  explicit OdeContact(bool tuned) : tuned_(tuned) {}
  ~OdeContact() override { destroy(); }
  std::string name() const override { return tuned_ ? "ode_tuned" : "ode_defaults"; }
  std::string family() const override { return "ode"; }
  std::string variant() const override { return tuned_ ? "tuned" : "defaults"; }
  std::string version() const override {
    return std::string("ODE (Debian libode-dev, double precision; configuration: ") +
           dGetConfiguration() + ")";
  }

  void reset(const ContactScenario& s, double dt) override {
    destroy();
    dt_ = dt;
    world_ = dWorldCreate();
    space_ = dSimpleSpaceCreate(nullptr);
    contacts_ = dJointGroupCreate(0);
    const Eigen::Vector3d& g = s.gravity_world;
    dWorldSetGravity(world_, g.x(), g.y(), g.z());
    const double rebound_speed = std::sqrt(2.0 * -g.z() * 1e-6);  // 4.4 mm/s
    if (tuned_) {
      dWorldSetContactSurfaceLayer(world_, 0.001 * kScale);
      // Before dBodyCreate: a body copies the world's auto-disable settings.
      dWorldSetAutoDisableFlag(world_, 1);
      dWorldSetAutoDisableLinearThreshold(world_,
                                          dWorldGetAutoDisableLinearThreshold(world_) * kScale);
      dWorldSetAutoDisableTime(world_, 0.1);
    }

    surface_ = dSurfaceParameters{};
    surface_.mode = dContactBounce;
    surface_.mu = s.board_material.friction;
    surface_.bounce = s.board_material.restitution;
    surface_.bounce_vel = 0.0;
    if (tuned_) {
      surface_.mode |= dContactApprox1 | dContactRolling;
      surface_.rho = s.board_material.rolling_resistance_m;
      surface_.rho2 = s.board_material.rolling_resistance_m;
      surface_.rhoN = s.board_material.spinning_friction_m;
      surface_.bounce_vel = rebound_speed;
    }

    const Eigen::Vector3d half = s.board.half_extent_m();
    const Eigen::Vector3d centre = s.board.centre_world();
    board_ = dCreateBox(space_, 2 * half.x(), 2 * half.y(), 2 * half.z());
    dGeomSetPosition(board_, centre.x(), centre.y(), centre.z());
    table_ = dCreatePlane(space_, 0, 0, 1, s.board.table_z_m());

    // The convex geom's data must outlive it: planes (n, n.p) and polygons (3, i, j, k).
    const LensHull hull = make_lens_hull(s.stone);
    points_.clear();
    planes_.clear();
    polygons_.clear();
    for (const Eigen::Vector3d& v : hull.vertices_body)
      points_.insert(points_.end(), {v.x(), v.y(), v.z()});
    for (const auto& t : hull.triangles) {
      const Eigen::Vector3d &a = hull.vertices_body[t[0]], &b = hull.vertices_body[t[1]],
                            &c = hull.vertices_body[t[2]];
      const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
      planes_.insert(planes_.end(), {n.x(), n.y(), n.z(), n.dot(a)});
      polygons_.insert(polygons_.end(), {3u, static_cast<unsigned>(t[0]),
                                         static_cast<unsigned>(t[1]), static_cast<unsigned>(t[2])});
    }
    body_ = dBodyCreate(world_);
    stone_ = dCreateConvex(space_, planes_.data(), static_cast<unsigned>(hull.triangles.size()),
                           points_.data(), static_cast<unsigned>(hull.vertices_body.size()),
                           polygons_.data());
    dGeomSetBody(stone_, body_);
    dMass m;
    dMassSetZero(&m);
    const Eigen::Vector3d& i = s.stone.principal_moments_body;
    dMassSetParameters(&m, s.stone.mass_kg, 0, 0, 0, i.x(), i.y(), i.z(), 0, 0, 0);
    dBodySetMass(body_, &m);
    const Eigen::Vector3d& x = s.initial.position_world;
    const Eigen::Quaterniond& q = s.initial.orientation;
    dBodySetPosition(body_, x.x(), x.y(), x.z());
    const dQuaternion dq = {q.w(), q.x(), q.y(), q.z()};
    dBodySetQuaternion(body_, dq);
    const Eigen::Vector3d& v = s.initial.velocity_world;
    const Eigen::Vector3d& w = s.initial_omega_world;
    dBodySetLinearVel(body_, v.x(), v.y(), v.z());
    dBodySetAngularVel(body_, w.x(), w.y(), w.z());
    if (s.rotation_frozen) {
      // An angular motor with three fixed world axes, zero target velocity and unbounded
      // torque locks the rotation (ODE manual, "Angular Motor").
      lock_ = dJointCreateAMotor(world_, nullptr);
      dJointAttach(lock_, body_, nullptr);
      dJointSetAMotorMode(lock_, dAMotorUser);
      dJointSetAMotorNumAxes(lock_, 3);
      dJointSetAMotorAxis(lock_, 0, 0, 1, 0, 0);
      dJointSetAMotorAxis(lock_, 1, 0, 0, 1, 0);
      dJointSetAMotorAxis(lock_, 2, 0, 0, 0, 1);
      for (int p : {dParamVel, dParamVel2, dParamVel3}) dJointSetAMotorParam(lock_, p, 0.0);
      for (int p : {dParamFMax, dParamFMax2, dParamFMax3})
        dJointSetAMotorParam(lock_, p, dInfinity);
    }

    std::string mode = "dContactBounce";
    if (surface_.mode & dContactApprox1) mode += " + dContactApprox1";
    if (surface_.mode & dContactRolling) mode += " + dContactRolling";
    settings_ = {
        {"stepping",
         "dWorldStep (exact LCP), one step per dt; dSimpleSpace, at most " +
             std::to_string(kMaxContacts) + " contacts per pair",
         "ODE manual, World (Stepping Functions), Collision Detection"},
        {"stone geom",
         "dConvex of the lens tessellation (" + std::to_string(hull.vertices_body.size()) +
             " points, " + std::to_string(hull.triangles.size()) + " faces) on a body",
         "ODE manual, Convex Class"},
        {"board, table", "static dBox (board), dPlane (table)", "ODE manual, Geometry Classes"},
        {"world ERP, CFM", num(dWorldGetERP(world_)) + ", " + num(dWorldGetCFM(world_)),
         "ODE manual, Joint error and the ERP; Soft constraint and CFM"},
        {"contact surface layer (m)", num(dWorldGetContactSurfaceLayer(world_)),
         "ODE manual, dWorldSetContactSurfaceLayer"},
        {"contact max correcting velocity (m/s)", num(dWorldGetContactMaxCorrectingVel(world_)),
         "ODE manual, dWorldSetContactMaxCorrectingVel"},
        {"contact mode", mode, "ODE manual, Contact (dSurfaceParameters)"},
        {"mu",
         num(surface_.mu) + ((surface_.mode & dContactApprox1)
                                 ? " (coefficient: friction <= mu N)"
                                 : " (force limit in N: friction <= mu)"),
         "ODE manual, Contact: dContactApprox1"},
        {"bounce, bounce_vel (m/s)", num(surface_.bounce) + ", " + num(surface_.bounce_vel),
         "ODE manual, Contact"},
        {"rolling rho, rho2 / spinning rhoN (m)",
         (surface_.mode & dContactRolling)
             ? num(surface_.rho) + ", " + num(surface_.rho2) + " / " + num(surface_.rhoN)
             : "off",
         "ODE manual, Contact: dContactRolling"},
        {"auto-disable: flag, linear (m/s), angular (rad/s), steps, time (s)",
         std::to_string(dBodyGetAutoDisableFlag(body_)) + ", " +
             num(dBodyGetAutoDisableLinearThreshold(body_)) + ", " +
             num(dBodyGetAutoDisableAngularThreshold(body_)) + ", " +
             std::to_string(dBodyGetAutoDisableSteps(body_)) + ", " +
             num(dBodyGetAutoDisableTime(body_)),
         "ODE manual, Automatic Enabling and Disabling"},
    };
  }

  void advance() override {
    if (abandoned_) return;
    std::jmp_buf jump;
    g_ode_jump = &jump;
    if (setjmp(jump) != 0) {
      g_ode_jump = nullptr;
      abandoned_ = true;
      g_ode_abandoned = true;
      failure_ = g_ode_error;
      return;
    }
    dSpaceCollide(space_, this, &OdeContact::near_callback);
    const int ok = dWorldStep(world_, dt_);
    dJointGroupEmpty(contacts_);
    g_ode_jump = nullptr;
    if (!ok) failure_ = "dWorldStep failed";
  }

  ContactSample sample() const override {
    if (abandoned_) {
      ContactSample nan;
      nan.position_world.setConstant(NAN);
      return nan;
    }
    const dReal* x = dBodyGetPosition(body_);
    const dReal* q = dBodyGetQuaternion(body_);
    const dReal* v = dBodyGetLinearVel(body_);
    const dReal* w = dBodyGetAngularVel(body_);
    ContactSample smp;
    smp.position_world = Eigen::Vector3d(x[0], x[1], x[2]);
    smp.orientation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
    smp.velocity_world = Eigen::Vector3d(v[0], v[1], v[2]);
    smp.omega_world = Eigen::Vector3d(w[0], w[1], w[2]);
    return smp;
  }

  bool asleep() const override { return !abandoned_ && !dBodyIsEnabled(body_); }
  std::string failure() const override { return failure_; }
  std::vector<Setting> settings() const override { return settings_; }

 private:
  static void near_callback(void* data, dGeomID a, dGeomID b) {
    auto* self = static_cast<OdeContact*>(data);
    if (dGeomGetBody(a) == nullptr && dGeomGetBody(b) == nullptr) return;  // board vs table
    dContact contact[kMaxContacts];
    const int n = dCollide(a, b, kMaxContacts, &contact[0].geom, sizeof(dContact));
    for (int k = 0; k < n; ++k) {
      // Debian's ODE collides dConvex with dBox through libccd, which returns a contact with a
      // zero normal when the stone touches the box exactly (depth 0): it carries no direction
      // and makes the step's LCP singular (NaN with a locked rotation), so it is dropped.
      const dReal* nrm = contact[k].geom.normal;
      if (nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2] < 0.5) {
        ++self->dropped_contacts_;
        continue;
      }
      contact[k].surface = self->surface_;
      const dJointID j = dJointCreateContact(self->world_, self->contacts_, &contact[k]);
      dJointAttach(j, dGeomGetBody(a), dGeomGetBody(b));
    }
  }
  void destroy() {
    if (abandoned_) {
      // Left inside a step by an internal error: leak it rather than run its destructors.
      contacts_ = nullptr;
      space_ = nullptr;
      world_ = nullptr;
      abandoned_ = false;
    }
    if (contacts_) dJointGroupDestroy(contacts_);
    if (space_) dSpaceDestroy(space_);  // destroys its geoms
    if (world_) dWorldDestroy(world_);  // destroys bodies and joints
    contacts_ = nullptr;
    space_ = nullptr;
    world_ = nullptr;
    lock_ = nullptr;
    failure_.clear();
  }

  bool tuned_;
  bool abandoned_ = false;
  long dropped_contacts_ = 0;
  double dt_ = 0.0;
  std::string failure_;
  std::vector<Setting> settings_;
  dWorldID world_ = nullptr;
  dSpaceID space_ = nullptr;
  dJointGroupID contacts_ = nullptr;
  dGeomID board_ = nullptr, table_ = nullptr, stone_ = nullptr;
  dBodyID body_ = nullptr;
  dJointID lock_ = nullptr;
  dSurfaceParameters surface_{};
  std::vector<dReal> points_, planes_;
  std::vector<unsigned> polygons_;
};

}  // namespace

std::unique_ptr<ContactMethod> make_ode_contact(bool tuned) {
  return std::make_unique<OdeContact>(tuned);
}
void init_contact_peers() {
  dInitODE2(0);
  dSetErrorHandler(&ode_fatal);
  dSetDebugHandler(&ode_fatal);
  dSetMessageHandler(&ode_message);
  init_mujoco_messages();
}
void shutdown_contact_peers() {
  if (!g_ode_abandoned) dCloseODE();
}

}  // namespace vg_bench
