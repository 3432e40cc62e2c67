// The peer engines, each set up the way its documentation suggests for one free rigid body:
// Bullet (btDiscreteDynamicsWorld), ODE (dWorldStep) and MuJoCo (free joint, mj_step).
#include <btBulletDynamicsCommon.h>
#include <mujoco/mujoco.h>
#include <ode/ode.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "bench.h"

namespace vg_bench {
namespace {

std::string fmt(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// ---- Bullet ----
class BulletMethod : public Method {
 public:
  // mass_scale multiplies mass and inertia alike (the motion is unchanged): 1e3 is the stone
  // in grams, which lifts its inertia above the threshold of Bullet's gyroscopic solve.
  BulletMethod(double mass_scale, std::vector<std::string>& notes)
      : mass_scale_(mass_scale), notes_(notes) {}
  ~BulletMethod() override { destroy(); }
  std::string name() const override { return mass_scale_ == 1.0 ? "bullet" : "bullet_grams"; }

  void reset(const Scenario& s, double dt) override {
    destroy();
    dt_ = dt;
    config_ = std::make_unique<btDefaultCollisionConfiguration>();
    dispatcher_ = std::make_unique<btCollisionDispatcher>(config_.get());
    broadphase_ = std::make_unique<btDbvtBroadphase>();
    solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
    world_ = std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(),
                                                       solver_.get(), config_.get());
    const Eigen::Vector3d& g = s.setup.gravity_world;
    world_->setGravity(btVector3(g.x(), g.y(), g.z()));
    // A rigid body needs a shape; a sphere of the stone's radius, alone in the world, never
    // collides. The inertia is given explicitly (not from the shape).
    shape_ = std::make_unique<btSphereShape>(0.011);
    const Eigen::Vector3d i = mass_scale_ * s.peer_inertia_body;
    btRigidBody::btRigidBodyConstructionInfo info(mass_scale_ * s.mass, nullptr, shape_.get(),
                                                  btVector3(i.x(), i.y(), i.z()));
    info.m_linearDamping = 0.0;  // the defaults, stated so nobody has to look them up
    info.m_angularDamping = 0.0;
    info.m_additionalDamping = false;
    body_ = std::make_unique<btRigidBody>(info);
    // Sleeping would freeze a body whose velocity fell below the thresholds; never here.
    body_->setActivationState(DISABLE_DEACTIVATION);
    world_->addRigidBody(body_.get());
    const Eigen::Vector3d& x = s.initial.position_world;
    const Eigen::Quaterniond& q = s.initial.orientation;
    btTransform t;
    t.setOrigin(btVector3(x.x(), x.y(), x.z()));
    t.setRotation(btQuaternion(q.x(), q.y(), q.z(), q.w()));  // btQuaternion is (x, y, z, w)
    body_->setCenterOfMassTransform(t);
    const Eigen::Vector3d& v = s.initial.velocity_world;
    const Eigen::Vector3d& w = s.initial_omega_world;
    body_->setLinearVelocity(btVector3(v.x(), v.y(), v.z()));
    body_->setAngularVelocity(btVector3(w.x(), w.y(), w.z()));  // world frame
    if (!noted_) {
      noted_ = true;
      notes_.push_back(
          "Bullet " + std::to_string(btGetVersion()) + " " + name() +
          " (double precision, mass "
          "and inertia x " +
          fmt(mass_scale_) + "): btRigidBody flags = " + std::to_string(body_->getFlags()) +
          " (8 = BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY, the default since 2.83), linear/angular "
          "damping 0, activation DISABLE_DEACTIVATION, stepSimulation(dt, 1, dt) = one internal "
          "step per call");
    }
  }

  void step() override { world_->stepSimulation(dt_, 1, dt_); }

  Sample sample() const override {
    const btTransform& t = body_->getCenterOfMassTransform();
    const btQuaternion r = t.getRotation();
    const btVector3 &x = t.getOrigin(), &v = body_->getLinearVelocity(),
                    &w = body_->getAngularVelocity();
    return Sample{Eigen::Vector3d(x.x(), x.y(), x.z()),
                  Eigen::Quaterniond(r.w(), r.x(), r.y(), r.z()),
                  Eigen::Vector3d(v.x(), v.y(), v.z()), Eigen::Vector3d(w.x(), w.y(), w.z())};
  }

 private:
  void destroy() {
    if (world_ && body_) world_->removeRigidBody(body_.get());
    body_.reset();
    shape_.reset();
    world_.reset();
    solver_.reset();
    broadphase_.reset();
    dispatcher_.reset();
    config_.reset();
  }
  double mass_scale_;
  std::vector<std::string>& notes_;
  bool noted_ = false;
  double dt_ = 0.0;
  std::unique_ptr<btDefaultCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btDbvtBroadphase> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  std::unique_ptr<btSphereShape> shape_;
  std::unique_ptr<btRigidBody> body_;
};

// ---- ODE ----
class OdeMethod : public Method {
 public:
  OdeMethod(bool finite, std::vector<std::string>& notes) : finite_(finite), notes_(notes) {}
  ~OdeMethod() override {
    if (world_) dWorldDestroy(world_);
  }
  std::string name() const override { return finite_ ? "ode_finite" : "ode"; }

  void reset(const Scenario& s, double dt) override {
    if (world_) dWorldDestroy(world_);
    dt_ = dt;
    world_ = dWorldCreate();
    const Eigen::Vector3d& g = s.setup.gravity_world;
    dWorldSetGravity(world_, g.x(), g.y(), g.z());
    body_ = dBodyCreate(world_);
    dMass m;
    dMassSetZero(&m);
    const Eigen::Vector3d& i = s.peer_inertia_body;
    // Centre of mass at the body origin, principal axes along the body axes.
    dMassSetParameters(&m, s.mass, 0, 0, 0, i.x(), i.y(), i.z(), 0, 0, 0);
    dBodySetMass(body_, &m);
    const Eigen::Vector3d& x = s.initial.position_world;
    const Eigen::Quaterniond& q = s.initial.orientation;
    dBodySetPosition(body_, x.x(), x.y(), x.z());
    const dQuaternion dq = {q.w(), q.x(), q.y(), q.z()};  // ODE is (w, x, y, z)
    dBodySetQuaternion(body_, dq);
    const Eigen::Vector3d& v = s.initial.velocity_world;
    const Eigen::Vector3d& w = s.initial_omega_world;
    dBodySetLinearVel(body_, v.x(), v.y(), v.z());
    dBodySetAngularVel(body_, w.x(), w.y(), w.z());  // world frame
    dBodySetFiniteRotationMode(body_, finite_ ? 1 : 0);
    if (!noted_) {
      noted_ = true;
      notes_.push_back("ODE " + name() + ": dWorldStep, finite rotation mode " +
                       std::to_string(dBodyGetFiniteRotationMode(body_)) + ", gyroscopic term " +
                       (dBodyGetGyroscopicMode(body_) ? "on" : "off") +
                       " (default), max angular speed " + fmt(dBodyGetMaxAngularSpeed(body_)) +
                       ", auto-disable " + std::to_string(dBodyGetAutoDisableFlag(body_)) +
                       ", damping " + fmt(dBodyGetLinearDamping(body_)) + "/" +
                       fmt(dBodyGetAngularDamping(body_)));
    }
  }

  void step() override {
    if (!dWorldStep(world_, dt_)) throw std::runtime_error("dWorldStep failed");
  }

  Sample sample() const override {
    const dReal* x = dBodyGetPosition(body_);
    const dReal* q = dBodyGetQuaternion(body_);
    const dReal* v = dBodyGetLinearVel(body_);
    const dReal* w = dBodyGetAngularVel(body_);
    return Sample{Eigen::Vector3d(x[0], x[1], x[2]), Eigen::Quaterniond(q[0], q[1], q[2], q[3]),
                  Eigen::Vector3d(v[0], v[1], v[2]), Eigen::Vector3d(w[0], w[1], w[2])};
  }

 private:
  bool finite_;
  std::vector<std::string>& notes_;
  bool noted_ = false;
  double dt_ = 0.0;
  dWorldID world_ = nullptr;
  dBodyID body_ = nullptr;
};

// ---- MuJoCo ----
class MujocoMethod : public Method {
 public:
  MujocoMethod(bool rk4, std::vector<std::string>& notes) : rk4_(rk4), notes_(notes) {}
  ~MujocoMethod() override { unload(); }
  std::string name() const override { return rk4_ ? "mujoco_rk4" : "mujoco_euler"; }

  void reset(const Scenario& s, double dt) override {
    if (!model_ || s.mass != loaded_mass_ || s.peer_inertia_body != loaded_inertia_ ||
        s.setup.gravity_world != loaded_gravity_) {
      load(s);
    }
    model_->opt.timestep = dt;
    mj_resetData(model_, data_);
    const Eigen::Vector3d& x = s.initial.position_world;
    const Eigen::Quaterniond& q = s.initial.orientation;
    const Eigen::Vector3d& v = s.initial.velocity_world;
    // Free joint: qpos = position, quaternion (w, x, y, z); qvel = world linear velocity, then
    // angular velocity in the BODY frame (MuJoCo issue #691).
    const Eigen::Vector3d w_body = q.conjugate() * s.initial_omega_world;
    const double qpos[7] = {x.x(), x.y(), x.z(), q.w(), q.x(), q.y(), q.z()};
    const double qvel[6] = {v.x(), v.y(), v.z(), w_body.x(), w_body.y(), w_body.z()};
    for (int k = 0; k < 7; ++k) data_->qpos[k] = qpos[k];
    for (int k = 0; k < 6; ++k) data_->qvel[k] = qvel[k];
  }

  void step() override { mj_step(model_, data_); }

  Sample sample() const override {
    const double* p = data_->qpos;
    const double* v = data_->qvel;
    const Eigen::Quaterniond q(p[3], p[4], p[5], p[6]);
    return Sample{Eigen::Vector3d(p[0], p[1], p[2]), q, Eigen::Vector3d(v[0], v[1], v[2]),
                  q * Eigen::Vector3d(v[3], v[4], v[5])};
  }

  // MuJoCo resets the state to qpos0 after a bad (huge or NaN) value and only warns; a run that
  // hit that must not be scored on the reset state.
  std::string failure() const override {
    if (data_->warning[mjWARN_BADQACC].number > 0) return "diverged (MuJoCo: bad qacc, reset)";
    if (data_->warning[mjWARN_BADQVEL].number > 0) return "diverged (MuJoCo: bad qvel, reset)";
    if (data_->warning[mjWARN_BADQPOS].number > 0) return "diverged (MuJoCo: bad qpos, reset)";
    return "";
  }

 private:
  void load(const Scenario& s) {
    unload();
    const Eigen::Vector3d& i = s.peer_inertia_body;
    const Eigen::Vector3d& g = s.setup.gravity_world;
    std::ostringstream xml;
    xml << "<mujoco model=\"stone\">\n"
        << "  <option integrator=\"" << (rk4_ ? "RK4" : "Euler") << "\" gravity=\"" << fmt(g.x())
        << " " << fmt(g.y()) << " " << fmt(g.z()) << "\"/>\n"
        << "  <worldbody>\n    <body name=\"stone\">\n      <freejoint/>\n"
        << "      <inertial pos=\"0 0 0\" mass=\"" << fmt(s.mass) << "\" diaginertia=\""
        << fmt(i.x()) << " " << fmt(i.y()) << " " << fmt(i.z()) << "\"/>\n"
        << "    </body>\n  </worldbody>\n</mujoco>\n";
    char path[] = "/tmp/vg_bench_mujoco_XXXXXX.xml";
    const int fd = mkstemps(path, 4);
    if (fd < 0) throw std::runtime_error("cannot create a temporary file for the MuJoCo model");
    const std::string text = xml.str();
    const bool written = write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
    close(fd);
    char error[1000] = "";
    model_ = written ? mj_loadXML(path, nullptr, error, sizeof error) : nullptr;
    unlink(path);
    if (!model_) throw std::runtime_error(std::string("MuJoCo could not load the model: ") + error);
    data_ = mj_makeData(model_);
    loaded_mass_ = s.mass;
    loaded_inertia_ = i;
    loaded_gravity_ = g;
    if (!noted_) {
      noted_ = true;
      notes_.push_back("MuJoCo " + std::to_string(mj_version()) + " " + name() +
                       ": one body with a free joint and an explicit <inertial> (compiled "
                       "inertia " +
                       fmt(model_->body_inertia[3]) + " " + fmt(model_->body_inertia[4]) + " " +
                       fmt(model_->body_inertia[5]) + ", mass " + fmt(model_->body_mass[1]) +
                       "), joint damping 0, mj_step");
    }
  }
  void unload() {
    if (data_) mj_deleteData(data_);
    if (model_) mj_deleteModel(model_);
    data_ = nullptr;
    model_ = nullptr;
  }
  bool rk4_;
  std::vector<std::string>& notes_;
  bool noted_ = false;
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
  double loaded_mass_ = 0.0;
  Eigen::Vector3d loaded_inertia_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d loaded_gravity_ = Eigen::Vector3d::Zero();
};

}  // namespace

std::unique_ptr<Method> make_bullet(double mass_scale, std::vector<std::string>& notes) {
  return std::make_unique<BulletMethod>(mass_scale, notes);
}
std::unique_ptr<Method> make_ode(bool finite_rotation, std::vector<std::string>& notes) {
  return std::make_unique<OdeMethod>(finite_rotation, notes);
}
std::unique_ptr<Method> make_mujoco(bool rk4, std::vector<std::string>& notes) {
  return std::make_unique<MujocoMethod>(rk4, notes);
}
void init_peers() { dInitODE2(0); }
void shutdown_peers() { dCloseODE(); }

}  // namespace vg_bench
