// Bullet with many stones: the contact benchmark's tuned set-up (contact/bullet_contact.cpp,
// "tuned for a 22 mm body" after the Bullet wiki's "Scaling The World" and the User Manual),
// one btConvexHullShape per colour shared by its stones, one btRigidBody per stone, in one
// btDiscreteDynamicsWorld (btDbvtBroadphase) stepped with stepSimulation(dt, 1, dt).
// Sleeping is Bullet's deactivation, on by default: a body whose speeds stay below its sleeping
// thresholds for gDeactivationTime (2 s) sleeps with its island
// (btRigidBody::setSleepingThresholds). Every pair gets the scene's one material through Bullet's
// combination rules: restitution and friction are the products of the two bodies'
// (btManifoldResult::calculateCombined*), so every body, static or not, carries sqrt(e) and
// sqrt(mu); the combined rolling friction is rolling_a mu_b + rolling_b mu_a, so every body carries
// l_r / (2 sqrt(mu)) (spinning alike).
#include <btBulletDynamicsCommon.h>

#include <memory>

#include "../contact/settings_format.h"
#include "many_method.h"

namespace vg_bench {
namespace {

// The contact benchmark's tuned values (contact/bullet_contact.cpp, bullet_settings()).
constexpr double kScale = 0.022;
constexpr double kMassScale = 1e3;
constexpr double kMargin = 0.04 * kScale;
constexpr double kRestitutionThreshold = 0.2 * kScale;
constexpr double kLinearSleep = 0.8 * kScale;
constexpr double kAngularSleep = 1.0;
constexpr double kContactProcessing = 1e-5;

class BulletMany : public ManyMethod {
 public:
  ~BulletMany() override { destroy(); }
  std::string name() const override { return "bullet"; }
  bool has_sleep() const override { return true; }
  std::string version() const override {
    const int v = btGetVersion();
    return "Bullet " + std::to_string(v / 100) + "." + std::to_string(v % 100) +
           " (Debian libbullet-dev, double precision)";
  }

  void reset(const ManyScene& s, double dt) override {
    destroy();
    dt_ = dt;
    config_ = std::make_unique<btDefaultCollisionConfiguration>();
    dispatcher_ = std::make_unique<btCollisionDispatcher>(config_.get());
    broadphase_ = std::make_unique<btDbvtBroadphase>();
    solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
    world_ = std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(),
                                                       solver_.get(), config_.get());
    const Eigen::Vector3d& g = s.gravity_world;
    world_->setGravity(btVector3(g.x(), g.y(), g.z()));
    btContactSolverInfo& info = world_->getSolverInfo();
    info.m_restitutionVelocityThreshold = kRestitutionThreshold;
    info.m_splitImpulsePenetrationThreshold = 0.0;

    const SurfaceMaterial& m = s.material;
    restitution_ = std::sqrt(m.restitution);
    friction_ = std::sqrt(m.friction);
    rolling_ = m.friction > 0.0 ? m.rolling_resistance_m / (2.0 * friction_) : 0.0;
    spinning_ = m.friction > 0.0 ? m.spinning_friction_m / (2.0 * friction_) : 0.0;

    if (s.board_enabled) {
      const Eigen::Vector3d half = s.board.half_extent_m();
      board_shape_ = std::make_unique<btBoxShape>(btVector3(half.x(), half.y(), half.z()));
      board_shape_->setMargin(kMargin);
      table_shape_ = std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), s.board.table_z_m());
      statics_.push_back(make_static(board_shape_.get(), s.board.centre_world()));
      statics_.push_back(make_static(table_shape_.get(), Eigen::Vector3d::Zero()));
    }
    black_shape_ = make_hull(s.black);
    white_shape_ = make_hull(s.white);
    for (std::size_t i = 0; i < s.stones.size(); ++i) {
      const ManyStone& st = s.stones[i];
      const StoneSpec& spec = s.spec(i);
      btConvexHullShape* shape =
          st.colour == Colour::black ? black_shape_.get() : white_shape_.get();
      const Eigen::Vector3d inertia = kMassScale * spec.principal_moments_body;
      btRigidBody::btRigidBodyConstructionInfo ci(kMassScale * spec.mass_kg, nullptr, shape,
                                                  btVector3(inertia.x(), inertia.y(), inertia.z()));
      ci.m_restitution = restitution_;
      ci.m_friction = friction_;
      ci.m_rollingFriction = rolling_;
      ci.m_spinningFriction = spinning_;
      ci.m_linearSleepingThreshold = kLinearSleep;
      ci.m_angularSleepingThreshold = kAngularSleep;
      auto body = std::make_unique<btRigidBody>(ci);
      body->setCcdMotionThreshold(spec.half_height_m);
      body->setCcdSweptSphereRadius(0.9 * spec.half_height_m);
      body->setContactProcessingThreshold(kContactProcessing);
      const Eigen::Vector3d& x = st.initial.position_world;
      const Eigen::Quaterniond& q = st.initial.orientation;
      btTransform t;
      t.setOrigin(btVector3(x.x(), x.y(), x.z()));
      t.setRotation(btQuaternion(q.x(), q.y(), q.z(), q.w()));
      body->setCenterOfMassTransform(t);
      const Eigen::Vector3d& v = st.initial.velocity_world;
      const Eigen::Vector3d& w = st.omega_world;
      body->setLinearVelocity(btVector3(v.x(), v.y(), v.z()));
      body->setAngularVelocity(btVector3(w.x(), w.y(), w.z()));
      world_->addRigidBody(body.get());
      stones_.push_back(std::move(body));
    }

    settings_ = {
        {"precision, stepping",
         "double; stepSimulation(dt, 1, dt): one internal step per dt; btDbvtBroadphase",
         "btDiscreteDynamicsWorld::stepSimulation"},
        {"stone shapes",
         "one btConvexHullShape per colour (" + std::to_string(black_shape_->getNumPoints()) +
             " points, the lens shrunk by the margin), shared by its stones",
         "User Manual, Collision Shapes and Collision Margin"},
        {"collision margin (m), mass x scale", num(kMargin) + ", x " + num(kMassScale),
         "wiki Scaling The World; flight benchmark (gyroscopic term)"},
        {"per body: restitution, friction, rolling, spinning (m)",
         num(restitution_) + ", " + num(friction_) + ", " + num(rolling_) + ", " + num(spinning_) +
             " (pairs: e " + num(m.restitution) + ", mu " + num(m.friction) + ", l_r " +
             num(m.rolling_resistance_m) + ", l_s " + num(m.spinning_friction_m) + ")",
         "btManifoldResult::calculateCombined* (products; rolling a mu_b + rolling b mu_a)"},
        {"restitution velocity threshold (m/s); split impulse threshold (m)",
         num(info.m_restitutionVelocityThreshold) + "; " +
             num(info.m_splitImpulsePenetrationThreshold),
         "btContactSolverInfo.h; User Manual, Split Impulse"},
        {"solver iterations, ERP (contact)",
         std::to_string(info.m_numIterations) + ", " + num(info.m_erp2), "btContactSolverInfo.h"},
        {"sleeping: thresholds (m/s, rad/s), time (s)",
         num(kLinearSleep) + ", " + num(kAngularSleep) + ", " + num(gDeactivationTime),
         "btRigidBody::setSleepingThresholds, gDeactivationTime"},
        {"contact processing threshold (m); CCD motion threshold, swept sphere",
         num(kContactProcessing) + "; c, 0.9 c",
         "btCollisionObject; User Manual, Continuous Collision Detection"},
    };
  }

  void advance() override { world_->stepSimulation(dt_, 1, dt_); }

  ContactSample sample(std::size_t i) const override {
    const btRigidBody& b = *stones_[i];
    const btTransform& t = b.getCenterOfMassTransform();
    const btQuaternion r = t.getRotation();
    const btVector3 &x = t.getOrigin(), &v = b.getLinearVelocity(), &w = b.getAngularVelocity();
    ContactSample smp;
    smp.position_world = Eigen::Vector3d(x.x(), x.y(), x.z());
    smp.orientation = Eigen::Quaterniond(r.w(), r.x(), r.y(), r.z());
    smp.velocity_world = Eigen::Vector3d(v.x(), v.y(), v.z());
    smp.omega_world = Eigen::Vector3d(w.x(), w.y(), w.z());
    return smp;
  }
  bool asleep(std::size_t i) const override {
    return stones_[i]->getActivationState() == ISLAND_SLEEPING;
  }
  std::vector<Setting> settings() const override { return settings_; }

 private:
  std::unique_ptr<btConvexHullShape> make_hull(const StoneSpec& spec) {
    // Hull + margin is the lens: the hull tessellates the inner parallel lens (spheres of
    // radius R - margin about the same centres).
    StoneSpec inner = spec;
    const double r = spec.sphere_radius_m() - kMargin, d = spec.sphere_offset_m();
    inner.half_height_m = r - d;
    inner.half_width_m = std::sqrt(r * r - d * d);
    const LensHull hull = make_lens_hull(inner);
    auto shape = std::make_unique<btConvexHullShape>();
    for (const Eigen::Vector3d& v : hull.vertices_body)
      shape->addPoint(btVector3(v.x(), v.y(), v.z()), false);
    shape->recalcLocalAabb();
    shape->setMargin(kMargin);
    return shape;
  }
  std::unique_ptr<btRigidBody> make_static(btCollisionShape* shape, const Eigen::Vector3d& at) {
    btRigidBody::btRigidBodyConstructionInfo ci(0.0, nullptr, shape);
    ci.m_restitution = restitution_;
    ci.m_friction = friction_;
    ci.m_rollingFriction = rolling_;
    ci.m_spinningFriction = spinning_;
    auto body = std::make_unique<btRigidBody>(ci);
    btTransform t;
    t.setIdentity();
    t.setOrigin(btVector3(at.x(), at.y(), at.z()));
    body->setWorldTransform(t);
    world_->addRigidBody(body.get());
    return body;
  }
  void destroy() {
    if (world_) {
      for (auto& b : stones_) world_->removeRigidBody(b.get());
      for (auto& b : statics_) world_->removeRigidBody(b.get());
    }
    stones_.clear();
    statics_.clear();
    black_shape_.reset();
    white_shape_.reset();
    board_shape_.reset();
    table_shape_.reset();
    world_.reset();
    solver_.reset();
    broadphase_.reset();
    dispatcher_.reset();
    config_.reset();
  }

  double dt_ = 0.0;
  double restitution_ = 0.0, friction_ = 0.0, rolling_ = 0.0, spinning_ = 0.0;
  std::vector<Setting> settings_;
  std::unique_ptr<btDefaultCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btDbvtBroadphase> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  std::unique_ptr<btBoxShape> board_shape_;
  std::unique_ptr<btStaticPlaneShape> table_shape_;
  std::unique_ptr<btConvexHullShape> black_shape_, white_shape_;
  std::vector<std::unique_ptr<btRigidBody>> statics_, stones_;
};

}  // namespace

std::unique_ptr<ManyMethod> make_bullet_many() { return std::make_unique<BulletMany>(); }

}  // namespace vg_bench
