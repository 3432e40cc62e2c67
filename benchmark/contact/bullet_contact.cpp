// Bullet: the stone as a btConvexHullShape of the tessellated lens, the board a static
// btBoxShape, the table a btStaticPlaneShape, one btDiscreteDynamicsWorld stepped with
// stepSimulation(dt, 1, dt) (one internal step per grid interval).
//
// Defaults: every setting as Bullet ships it; only what the scenario asks for is set, the way
// the Bullet User Manual tells (restitution and friction on the bodies: the pair's values are
// the products of the two bodies', btManifoldResult::calculateCombined*, so the static bodies
// carry 1 and the stone e and mu).
// Tuned for a 22 mm body, following the Bullet wiki's "Scaling The World" (Bullet is designed
// for bodies of 0.05 to 10 units; scale every linear tolerance by the body's size) and the
// Bullet User Manual (collision margin, continuous collision detection, rolling friction):
// every linear default scaled by X = 0.022 (the stone's width over 1 m), the hull shrunk by
// its margin so that hull + margin is the lens, CCD on, rolling and spinning friction, and the
// mass in grams (Bullet's implicit gyroscopic term is skipped for inertias ~1e-7 kg m^2; see
// the flight benchmark's engine limits).
#include <btBulletDynamicsCommon.h>

#include <memory>

#include "contact_method.h"
#include "settings_format.h"

namespace vg_bench {
namespace {

constexpr double kScale = 0.022;  // X: the stone's width (m) over Bullet's 1-unit body

struct BulletSettings {
  bool tuned = false;
  double mass_scale = 1.0;
  double margin_m = NAN;  // NaN: Bullet's default (read back)
  bool shrink_hull = false;
  double restitution_velocity_threshold_mps = NAN;
  double split_impulse_penetration_threshold_m = NAN;
  double linear_sleeping_threshold_mps = NAN;
  double angular_sleeping_threshold_radps = NAN;
  double ccd_motion_threshold_m = 0.0;
  double ccd_swept_sphere_radius_m = 0.0;
  bool rolling_friction = false;
  double contact_processing_threshold_m = NAN;  // NaN: Bullet's default (BT_LARGE_FLOAT)
};

BulletSettings bullet_settings(bool tuned, const ContactScenario& s) {
  BulletSettings b;
  b.tuned = tuned;
  if (!tuned) return b;
  b.mass_scale = 1e3;
  b.margin_m = 0.04 * kScale;
  b.shrink_hull = true;
  b.restitution_velocity_threshold_mps = 0.2 * kScale;
  // Split impulse for every penetration: the default -0.04 m (and even -0.04 X) leaves every
  // penetration of a 5 cm drop to the Baumgarte term, which throws the stone back up faster
  // than its restitution says (velocity error + erp * depth / dt).
  b.split_impulse_penetration_threshold_m = 0.0;
  b.linear_sleeping_threshold_mps = 0.8 * kScale;
  b.angular_sleeping_threshold_radps = 1.0;  // angular velocities do not scale with size
  b.ccd_motion_threshold_m = s.stone.half_height_m;
  b.ccd_swept_sphere_radius_m = 0.9 * s.stone.half_height_m;  // inside the lens
  b.rolling_friction = true;
  // Solve only contacts closer than 10 um: a contact still apart by d gets the target velocity
  // e |v| - d / dt (btSequentialImpulseConstraintSolver::setupContactConstraint), which cancels
  // the bounce of a stone caught one step before it touches (the default solves every contact
  // in the manifold, BT_LARGE_FLOAT; btCollisionObject.h calls it "0 by default"). With 0 a
  // resting stone's contact, at +1e-17 m, drops out now and then and the stone falls a step.
  b.contact_processing_threshold_m = 1e-5;
  return b;
}

class BulletContact : public ContactMethod {
 public:
  explicit BulletContact(bool tuned) : tuned_(tuned) {}
  ~BulletContact() override { destroy(); }
  std::string name() const override { return tuned_ ? "bullet_tuned" : "bullet_defaults"; }
  std::string family() const override { return "bullet"; }
  std::string variant() const override { return tuned_ ? "tuned" : "defaults"; }
  std::string version() const override {
    const int v = btGetVersion();  // 324 for 3.24
    return "Bullet " + std::to_string(v / 100) + "." + std::to_string(v % 100) +
           " (Debian libbullet-dev, double precision)";
  }

  void reset(const ContactScenario& s, double dt) override {
    destroy();
    dt_ = dt;
    const BulletSettings b = bullet_settings(tuned_, s);
    config_ = std::make_unique<btDefaultCollisionConfiguration>();
    dispatcher_ = std::make_unique<btCollisionDispatcher>(config_.get());
    broadphase_ = std::make_unique<btDbvtBroadphase>();
    solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
    world_ = std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(),
                                                       solver_.get(), config_.get());
    const Eigen::Vector3d& g = s.gravity_world;
    world_->setGravity(btVector3(g.x(), g.y(), g.z()));
    btContactSolverInfo& info = world_->getSolverInfo();
    if (!std::isnan(b.restitution_velocity_threshold_mps))
      info.m_restitutionVelocityThreshold = b.restitution_velocity_threshold_mps;
    if (!std::isnan(b.split_impulse_penetration_threshold_m))
      info.m_splitImpulsePenetrationThreshold = b.split_impulse_penetration_threshold_m;

    // The board and the table: static (mass 0), restitution and friction 1 so that the pair's
    // products are the stone's values; rolling and spinning friction 0 (the pair's combined
    // rolling friction is stone_rolling * board_friction + board_rolling * stone_friction).
    const Eigen::Vector3d half = s.board.half_extent_m();
    board_shape_ = std::make_unique<btBoxShape>(btVector3(half.x(), half.y(), half.z()));
    if (!std::isnan(b.margin_m)) board_shape_->setMargin(b.margin_m);
    table_shape_ = std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), s.board.table_z_m());
    board_ = make_static(board_shape_.get(), s.board.centre_world());
    table_ = make_static(table_shape_.get(), Eigen::Vector3d::Zero());

    // The stone. Bullet adds the margin around the hull's points, so the tuned hull is the
    // tessellation of the inner parallel lens (spheres of radius R - margin about the same
    // centres: half-thickness c - margin): hull + margin is the lens, its rim rounded by the
    // margin, with as many points as the plain tessellation.
    StoneSpec inner = s.stone;
    if (b.shrink_hull) {
      const double r = s.stone.sphere_radius_m() - b.margin_m, d = s.stone.sphere_offset_m();
      inner.half_height_m = r - d;
      inner.half_width_m = std::sqrt(r * r - d * d);
    }
    const LensHull hull = make_lens_hull(inner);
    stone_shape_ = std::make_unique<btConvexHullShape>();
    for (const Eigen::Vector3d& v : hull.vertices_body)
      stone_shape_->addPoint(btVector3(v.x(), v.y(), v.z()), false);
    stone_shape_->recalcLocalAabb();
    if (!std::isnan(b.margin_m)) stone_shape_->setMargin(b.margin_m);
    const Eigen::Vector3d inertia = b.mass_scale * s.stone.principal_moments_body;
    btRigidBody::btRigidBodyConstructionInfo ci(b.mass_scale * s.stone.mass_kg, nullptr,
                                                stone_shape_.get(),
                                                btVector3(inertia.x(), inertia.y(), inertia.z()));
    ci.m_restitution = s.board_material.restitution;
    ci.m_friction = s.board_material.friction;
    if (b.rolling_friction) {
      ci.m_rollingFriction = s.board_material.rolling_resistance_m;
      ci.m_spinningFriction = s.board_material.spinning_friction_m;
    }
    if (!std::isnan(b.linear_sleeping_threshold_mps)) {
      ci.m_linearSleepingThreshold = b.linear_sleeping_threshold_mps;
      ci.m_angularSleepingThreshold = b.angular_sleeping_threshold_radps;
    }
    stone_ = std::make_unique<btRigidBody>(ci);
    stone_->setCcdMotionThreshold(b.ccd_motion_threshold_m);
    stone_->setCcdSweptSphereRadius(b.ccd_swept_sphere_radius_m);
    if (!std::isnan(b.contact_processing_threshold_m))
      stone_->setContactProcessingThreshold(b.contact_processing_threshold_m);
    if (s.rotation_frozen) stone_->setAngularFactor(0.0);
    const Eigen::Vector3d& x = s.initial.position_world;
    const Eigen::Quaterniond& q = s.initial.orientation;
    btTransform t;
    t.setOrigin(btVector3(x.x(), x.y(), x.z()));
    t.setRotation(btQuaternion(q.x(), q.y(), q.z(), q.w()));
    stone_->setCenterOfMassTransform(t);
    const Eigen::Vector3d& v = s.initial.velocity_world;
    const Eigen::Vector3d& w = s.initial_omega_world;
    stone_->setLinearVelocity(btVector3(v.x(), v.y(), v.z()));
    stone_->setAngularVelocity(btVector3(w.x(), w.y(), w.z()));
    world_->addRigidBody(stone_.get());

    settings_ = {
        {"precision, stepping", "double; stepSimulation(dt, 1, dt): one internal step per dt",
         "btDiscreteDynamicsWorld::stepSimulation (btDynamicsWorld.h)"},
        {"stone shape",
         "btConvexHullShape of the lens tessellation (" +
             std::to_string(stone_shape_->getNumPoints()) + " points" +
             (b.shrink_hull ? ", of the lens shrunk by the margin" : "") + ")",
         "User Manual, Collision Shapes and Collision Margin"},
        {"board, table", "btBoxShape (board), btStaticPlaneShape (table), static bodies",
         "User Manual, Collision Shapes"},
        {"collision margin (m)",
         "stone " + num(stone_shape_->getMargin()) + ", board " + num(board_shape_->getMargin()),
         "User Manual, Collision Margin; wiki Scaling The World"},
        {"mass (kg) x scale", num(s.stone.mass_kg) + " x " + num(b.mass_scale),
         "flight benchmark: gyroscopic term skipped below 2.2e-16 determinant"},
        {"restitution (stone x static)", num(stone_->getRestitution()) + " x 1",
         "btManifoldResult::calculateCombinedRestitution (product)"},
        {"friction (stone x static)", num(stone_->getFriction()) + " x 1",
         "btManifoldResult::calculateCombinedFriction (product)"},
        {"rolling / spinning friction (m)",
         num(stone_->getRollingFriction()) + " / " + num(stone_->getSpinningFriction()),
         "btCollisionObject::setRollingFriction, setSpinningFriction"},
        {"restitution velocity threshold (m/s)", num(info.m_restitutionVelocityThreshold),
         "btContactSolverInfo.h (zero restitution below it)"},
        {"split impulse, penetration threshold (m)",
         std::string(info.m_splitImpulse ? "on" : "off") + ", " +
             num(info.m_splitImpulsePenetrationThreshold),
         "btContactSolverInfo.h; User Manual, Split Impulse"},
        {"solver iterations, ERP (contact)",
         std::to_string(info.m_numIterations) + ", " + num(info.m_erp2), "btContactSolverInfo.h"},
        {"sleeping thresholds (m/s, rad/s), time (s)",
         num(stone_->getLinearSleepingThreshold()) + ", " +
             num(stone_->getAngularSleepingThreshold()) + ", " + num(gDeactivationTime),
         "btRigidBody::setSleepingThresholds, gDeactivationTime"},
        {"contact processing threshold (m)", num(stone_->getContactProcessingThreshold()),
         "btCollisionObject::setContactProcessingThreshold"},
        {"CCD motion threshold, swept sphere radius (m)",
         num(stone_->getCcdMotionThreshold()) + ", " + num(stone_->getCcdSweptSphereRadius()),
         "User Manual, Continuous Collision Detection"},
    };
  }

  void advance() override { world_->stepSimulation(dt_, 1, dt_); }

  ContactSample sample() const override {
    const btTransform& t = stone_->getCenterOfMassTransform();
    const btQuaternion r = t.getRotation();
    const btVector3 &x = t.getOrigin(), &v = stone_->getLinearVelocity(),
                    &w = stone_->getAngularVelocity();
    ContactSample smp;
    smp.position_world = Eigen::Vector3d(x.x(), x.y(), x.z());
    smp.orientation = Eigen::Quaterniond(r.w(), r.x(), r.y(), r.z());
    smp.velocity_world = Eigen::Vector3d(v.x(), v.y(), v.z());
    smp.omega_world = Eigen::Vector3d(w.x(), w.y(), w.z());
    return smp;
  }

  bool asleep() const override { return stone_->getActivationState() == ISLAND_SLEEPING; }
  std::vector<Setting> settings() const override { return settings_; }

 private:
  std::unique_ptr<btRigidBody> make_static(btCollisionShape* shape, const Eigen::Vector3d& at) {
    btRigidBody::btRigidBodyConstructionInfo ci(0.0, nullptr, shape);
    ci.m_restitution = 1.0;
    ci.m_friction = 1.0;
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
      if (stone_) world_->removeRigidBody(stone_.get());
      if (board_) world_->removeRigidBody(board_.get());
      if (table_) world_->removeRigidBody(table_.get());
    }
    stone_.reset();
    board_.reset();
    table_.reset();
    stone_shape_.reset();
    board_shape_.reset();
    table_shape_.reset();
    world_.reset();
    solver_.reset();
    broadphase_.reset();
    dispatcher_.reset();
    config_.reset();
  }

  bool tuned_;
  double dt_ = 0.0;
  std::vector<Setting> settings_;
  std::unique_ptr<btDefaultCollisionConfiguration> config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btDbvtBroadphase> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  std::unique_ptr<btBoxShape> board_shape_;
  std::unique_ptr<btStaticPlaneShape> table_shape_;
  std::unique_ptr<btConvexHullShape> stone_shape_;
  std::unique_ptr<btRigidBody> board_, table_, stone_;
};

}  // namespace

std::unique_ptr<ContactMethod> make_bullet_contact(bool tuned) {
  return std::make_unique<BulletContact>(tuned);
}

}  // namespace vg_bench
