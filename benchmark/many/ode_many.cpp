// ODE with many stones: the contact benchmark's tuned surface and world (contact/ode_contact.cpp,
// "tuned for a 22 mm body" after the ODE manual), with what the manual says for many bodies:
// a dHashSpace instead of a dSimpleSpace (Collision Detection, Space functions: the simple
// space tests every pair), dWorldQuickStep (World, Stepping Functions: "for large systems";
// dWorldStep's big-matrix LCP grows as the cube of the constraint rows of an island), and
// auto-disable (Automatic Enabling and Disabling) as ODE's sleeping. The near callback skips
// pairs whose bodies are all disabled (ODE still reports them; the manual's demos filter pairs
// in the callback), so a disabled stone costs no narrow phase against the board or another
// disabled stone. One surface for every pair (the scene's material).
#include <ode/ode.h>

#include <cstdarg>
#include <cstdio>
#include <memory>

#include "../contact/settings_format.h"
#include "many_method.h"

namespace vg_bench {
namespace {

constexpr double kScale = 0.022;
constexpr int kMaxContacts = 8;

void ode_fatal(int errnum, const char* msg, va_list ap) {
  std::fprintf(stderr, "ODE internal error %d: ", errnum);
  std::vfprintf(stderr, msg, ap);
  std::fprintf(stderr, "\n");
  std::abort();
}
long g_ode_messages = 0;
void ode_message(int, const char*, va_list) { ++g_ode_messages; }

struct ConvexData {
  std::vector<dReal> points, planes;
  std::vector<unsigned> polygons;
};

ConvexData convex_of(const StoneSpec& spec) {
  const LensHull hull = make_lens_hull(spec);
  ConvexData c;
  for (const Eigen::Vector3d& v : hull.vertices_body)
    c.points.insert(c.points.end(), {v.x(), v.y(), v.z()});
  for (const auto& t : hull.triangles) {
    const Eigen::Vector3d &a = hull.vertices_body[t[0]], &b = hull.vertices_body[t[1]],
                          &d = hull.vertices_body[t[2]];
    const Eigen::Vector3d n = (b - a).cross(d - a).normalized();
    c.planes.insert(c.planes.end(), {n.x(), n.y(), n.z(), n.dot(a)});
    c.polygons.insert(c.polygons.end(), {3u, static_cast<unsigned>(t[0]),
                                         static_cast<unsigned>(t[1]), static_cast<unsigned>(t[2])});
  }
  return c;
}

class OdeMany : public ManyMethod {
 public:
  ~OdeMany() override { destroy(); }
  std::string name() const override { return "ode"; }
  bool has_sleep() const override { return true; }
  std::string version() const override {
    return std::string("ODE (Debian libode-dev, double precision; configuration: ") +
           dGetConfiguration() + ")";
  }

  void reset(const ManyScene& s, double dt) override {
    destroy();
    dt_ = dt;
    world_ = dWorldCreate();
    space_ = dHashSpaceCreate(nullptr);
    dHashSpaceSetLevels(space_, -6, 1);  // cells from 1/64 m (a stone) to 2 m (the board)
    contacts_ = dJointGroupCreate(0);
    const Eigen::Vector3d& g = s.gravity_world;
    dWorldSetGravity(world_, g.x(), g.y(), g.z());
    dWorldSetContactSurfaceLayer(world_, 0.001 * kScale);
    dWorldSetAutoDisableFlag(world_, 1);
    dWorldSetAutoDisableLinearThreshold(world_,
                                        dWorldGetAutoDisableLinearThreshold(world_) * kScale);
    dWorldSetAutoDisableTime(world_, 0.1);

    const double rebound_speed = std::sqrt(2.0 * 9.80665 * 1e-6);  // 4.4 mm/s
    surface_ = dSurfaceParameters{};
    surface_.mode = dContactBounce | dContactApprox1 | dContactRolling;
    surface_.mu = s.material.friction;
    surface_.bounce = s.material.restitution;
    surface_.bounce_vel = rebound_speed;
    surface_.rho = s.material.rolling_resistance_m;
    surface_.rho2 = s.material.rolling_resistance_m;
    surface_.rhoN = s.material.spinning_friction_m;

    if (s.board_enabled) {
      const Eigen::Vector3d half = s.board.half_extent_m();
      const Eigen::Vector3d centre = s.board.centre_world();
      dGeomID board = dCreateBox(space_, 2 * half.x(), 2 * half.y(), 2 * half.z());
      dGeomSetPosition(board, centre.x(), centre.y(), centre.z());
      dCreatePlane(space_, 0, 0, 1, s.board.table_z_m());
    }
    black_ = convex_of(s.black);
    white_ = convex_of(s.white);
    for (std::size_t i = 0; i < s.stones.size(); ++i) {
      const ManyStone& st = s.stones[i];
      const StoneSpec& spec = s.spec(i);
      ConvexData& c = st.colour == Colour::black ? black_ : white_;
      dBodyID body = dBodyCreate(world_);
      dGeomID geom = dCreateConvex(space_, c.planes.data(),
                                   static_cast<unsigned>(c.polygons.size() / 4), c.points.data(),
                                   static_cast<unsigned>(c.points.size() / 3), c.polygons.data());
      dGeomSetBody(geom, body);
      dMass m;
      dMassSetZero(&m);
      const Eigen::Vector3d& in = spec.principal_moments_body;
      dMassSetParameters(&m, spec.mass_kg, 0, 0, 0, in.x(), in.y(), in.z(), 0, 0, 0);
      dBodySetMass(body, &m);
      const Eigen::Vector3d& x = st.initial.position_world;
      const Eigen::Quaterniond& q = st.initial.orientation;
      dBodySetPosition(body, x.x(), x.y(), x.z());
      const dQuaternion dq = {q.w(), q.x(), q.y(), q.z()};
      dBodySetQuaternion(body, dq);
      const Eigen::Vector3d& v = st.initial.velocity_world;
      const Eigen::Vector3d& w = st.omega_world;
      dBodySetLinearVel(body, v.x(), v.y(), v.z());
      dBodySetAngularVel(body, w.x(), w.y(), w.z());
      bodies_.push_back(body);
    }

    settings_ = {
        {"stepping",
         "dWorldQuickStep (" + std::to_string(dWorldGetQuickStepNumIterations(world_)) +
             " iterations, SOR " + num(dWorldGetQuickStepW(world_)) +
             "), one step per dt; dHashSpace levels -6..1; at most " +
             std::to_string(kMaxContacts) + " contacts per pair",
         "ODE manual, World (Stepping Functions), Collision Detection (Spaces)"},
        {"stone geoms",
         "dConvex of the lens tessellation (" + std::to_string(black_.points.size() / 3) +
             " points) per stone",
         "ODE manual, Convex Class"},
        {"world ERP, CFM; surface layer (m)",
         num(dWorldGetERP(world_)) + ", " + num(dWorldGetCFM(world_)) + "; " +
             num(dWorldGetContactSurfaceLayer(world_)),
         "ODE manual, World"},
        {"contact (every pair)",
         "dContactBounce + dContactApprox1 + dContactRolling; mu " + num(surface_.mu) +
             " (coefficient), bounce " + num(surface_.bounce) + ", bounce_vel " +
             num(surface_.bounce_vel) + " m/s, rho " + num(surface_.rho) + " m, rhoN " +
             num(surface_.rhoN) + " m",
         "ODE manual, Contact"},
        {"auto-disable: linear (m/s), angular (rad/s), steps, time (s)",
         num(dWorldGetAutoDisableLinearThreshold(world_)) + ", " +
             num(dWorldGetAutoDisableAngularThreshold(world_)) + ", " +
             std::to_string(dWorldGetAutoDisableSteps(world_)) + ", " +
             num(dWorldGetAutoDisableTime(world_)) + "; pairs of disabled bodies are not collided",
         "ODE manual, Automatic Enabling and Disabling"},
    };
  }

  void advance() override {
    dSpaceCollide(space_, this, &near_callback);
    dWorldQuickStep(world_, dt_);
    dJointGroupEmpty(contacts_);
  }

  ContactSample sample(std::size_t i) const override {
    dBodyID b = bodies_[i];
    const dReal* x = dBodyGetPosition(b);
    const dReal* q = dBodyGetQuaternion(b);
    const dReal* v = dBodyGetLinearVel(b);
    const dReal* w = dBodyGetAngularVel(b);
    ContactSample smp;
    smp.position_world = Eigen::Vector3d(x[0], x[1], x[2]);
    smp.orientation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
    smp.velocity_world = Eigen::Vector3d(v[0], v[1], v[2]);
    smp.omega_world = Eigen::Vector3d(w[0], w[1], w[2]);
    return smp;
  }
  bool asleep(std::size_t i) const override { return !dBodyIsEnabled(bodies_[i]); }
  std::string failure() const override {
    return g_ode_messages > 0 ? std::to_string(g_ode_messages) + " ODE messages" : "";
  }
  std::vector<Setting> settings() const override { return settings_; }

 private:
  static void near_callback(void* data, dGeomID a, dGeomID b) {
    auto* self = static_cast<OdeMany*>(data);
    const dBodyID ba = dGeomGetBody(a), bb = dGeomGetBody(b);
    const bool awake_a = ba && dBodyIsEnabled(ba), awake_b = bb && dBodyIsEnabled(bb);
    if (!awake_a && !awake_b) return;  // static-static, or nothing awake in the pair
    dContact contact[kMaxContacts];
    const int n = dCollide(a, b, kMaxContacts, &contact[0].geom, sizeof(dContact));
    for (int k = 0; k < n; ++k) {
      // As in the contact benchmark: libccd's contacts with a zero normal at depth 0 carry no
      // direction and make the step singular; they are dropped.
      const dReal* nrm = contact[k].geom.normal;
      if (nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2] < 0.5) continue;
      contact[k].surface = self->surface_;
      const dJointID j = dJointCreateContact(self->world_, self->contacts_, &contact[k]);
      dJointAttach(j, ba, bb);
    }
  }
  void destroy() {
    if (contacts_) dJointGroupDestroy(contacts_);
    if (space_) dSpaceDestroy(space_);
    if (world_) dWorldDestroy(world_);
    contacts_ = nullptr;
    space_ = nullptr;
    world_ = nullptr;
    bodies_.clear();
  }

  double dt_ = 0.0;
  std::vector<Setting> settings_;
  dWorldID world_ = nullptr;
  dSpaceID space_ = nullptr;
  dJointGroupID contacts_ = nullptr;
  std::vector<dBodyID> bodies_;
  dSurfaceParameters surface_{};
  ConvexData black_, white_;
};

}  // namespace

std::unique_ptr<ManyMethod> make_ode_many() { return std::make_unique<OdeMany>(); }

void init_many_peers() {
  dInitODE2(0);
  dSetErrorHandler(&ode_fatal);
  dSetDebugHandler(&ode_fatal);
  dSetMessageHandler(&ode_message);
  init_mujoco_many_messages();
}
void shutdown_many_peers() { dCloseODE(); }

}  // namespace vg_bench
