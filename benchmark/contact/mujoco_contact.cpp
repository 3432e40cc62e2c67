// MuJoCo: the stone as a mesh geom (MuJoCo collides its convex hull) of the tessellated lens on
// a body with a free joint and explicit <inertial>, the board a box geom, the table a plane;
// mj_step with timestep = dt, one step per grid interval. The stone's geom has priority, so its
// contact parameters are the pair's (MuJoCo docs, Modeling: Contact parameters).
//
// MuJoCo has no restitution coefficient: its contacts are soft constraints whose reference
// acceleration is a damped spring, solref = (timeconst, dampratio) (Modeling: Solver
// parameters). Bouncing a linear damped spring gives e = exp(-pi z / sqrt(1 - z^2)) for a
// damping ratio z, so each variant gets dampratio = -ln e / sqrt(pi^2 + ln^2 e) (0.2155 for
// e = 0.5, 0.0709 for 0.8; Modeling: Restitution).
// Defaults: MuJoCo's defaults (Euler, pyramidal cones, condim 3, timeconst 0.02 s, solimp
// 0.9 0.95 0.001) with the scenario's mu and that dampratio.
// Tuned for the stone (XML reference: option, geom): timeconst 2 ms (MuJoCo raises it to 2 dt
// for coarser steps, flag refsafe), a stiffer impedance whose transition width is scaled to the
// body, condim 6 with the torsional and rolling friction lengths l_s and l_r, elliptic friction
// cones and the noslip post-solver against creep, several contact points per mesh pair
// (multiccd).
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <sstream>

#include "contact_method.h"
#include "settings_format.h"

namespace vg_bench {
namespace {

double damping_ratio_for_restitution(double e) {
  if (e <= 0.0) return 1.0;
  const double l = std::log(e);
  return -l / std::sqrt(M_PI * M_PI + l * l);
}

// The contact spring's natural frequency is 1 / (timeconst dampratio) (k = 1 / (timeconst
// dampratio)^2 at full impedance), so MuJoCo's rule "timeconst at least 2 dt", written for
// dampratio 1, becomes timeconst >= 2 dt / dampratio for a bouncing contact; below that the
// explicit spring is unstable (the drop then gains energy at every bounce).
double tuned_timeconst(double dt, double zeta) { return std::max(0.002, 2.0 * dt / zeta); }
// A constant impedance d = 0.99 (dmin = dmax): the contact is then a linear spring-damper,
// for which the dampratio mapping above holds, and stiff (the sinking at rest is about
// (1 - d) g (timeconst dampratio)^2).
constexpr const char* kTunedSolimp = "0.99 0.99 0.001 0.5 2";

class MujocoContact : public ContactMethod {
 public:
  explicit MujocoContact(bool tuned) : tuned_(tuned) {}
  ~MujocoContact() override { unload(); }
  std::string name() const override { return tuned_ ? "mujoco_tuned" : "mujoco_defaults"; }
  std::string family() const override { return "mujoco"; }
  std::string variant() const override { return tuned_ ? "tuned" : "defaults"; }
  std::string version() const override {
    const int v = mj_version();  // 222 for 2.2.2
    return "MuJoCo " + std::to_string(v / 100) + "." + std::to_string(v / 10 % 10) + "." +
           std::to_string(v % 10) + " (Debian libmujoco-dev)";
  }

  void reset(const ContactScenario& s, double dt) override {
    unload();
    const double zeta = damping_ratio_for_restitution(s.board_material.restitution);
    const SurfaceMaterial& mat = s.board_material;
    std::ostringstream xml;
    xml.precision(17);
    const Eigen::Vector3d half = s.board.half_extent_m(), centre = s.board.centre_world();
    const Eigen::Vector3d& g = s.gravity_world;
    const Eigen::Vector3d& i = s.stone.principal_moments_body;
    xml << "<mujoco model=\"stone_on_board\">\n"
        << "  <option timestep=\"" << dt << "\" gravity=\"" << g.x() << " " << g.y() << " " << g.z()
        << "\"";
    if (tuned_) xml << " cone=\"elliptic\" noslip_iterations=\"10\"";
    xml << ">\n";
    // Several contact points per geom pair from the convex-convex collider (XML reference,
    // option/flag multiccd, marked experimental in 2.2): without it a mesh resting on a facet
    // gets one point per step and wobbles.
    if (tuned_) xml << "    <flag multiccd=\"enable\"/>\n";
    xml << "  </option>\n  <asset>\n    <mesh name=\"lens\" vertex=\"";
    const LensHull hull = make_lens_hull(s.stone);
    for (const Eigen::Vector3d& v : hull.vertices_body)
      xml << v.x() << " " << v.y() << " " << v.z() << " ";
    xml << "\"/>\n  </asset>\n  <worldbody>\n"
        << "    <geom name=\"table\" type=\"plane\" size=\"0 0 1\" pos=\"0 0 "
        << s.board.table_z_m() << "\"/>\n"
        << "    <geom name=\"board\" type=\"box\" size=\"" << half.x() << " " << half.y() << " "
        << half.z() << "\" pos=\"" << centre.x() << " " << centre.y() << " " << centre.z()
        << "\"/>\n"
        << "    <body name=\"stone\"";
    const Eigen::Vector3d& x = s.initial.position_world;
    if (s.rotation_frozen) xml << " pos=\"" << x.x() << " " << x.y() << " " << x.z() << "\"";
    xml << ">\n";
    if (s.rotation_frozen) {
      // Translation only: three slide joints (XML reference, joint).
      xml << "      <joint name=\"x\" type=\"slide\" axis=\"1 0 0\"/>\n"
          << "      <joint name=\"y\" type=\"slide\" axis=\"0 1 0\"/>\n"
          << "      <joint name=\"z\" type=\"slide\" axis=\"0 0 1\"/>\n";
    } else {
      xml << "      <freejoint/>\n";
    }
    xml << "      <inertial pos=\"0 0 0\" mass=\"" << s.stone.mass_kg << "\" diaginertia=\""
        << i.x() << " " << i.y() << " " << i.z() << "\"/>\n"
        << "      <geom name=\"lens\" type=\"mesh\" mesh=\"lens\" priority=\"1\"";
    if (tuned_) {
      xml << " condim=\"6\" friction=\"" << mat.friction << " " << mat.spinning_friction_m << " "
          << mat.rolling_resistance_m << "\" solref=\"" << tuned_timeconst(dt, zeta) << " " << zeta
          << "\" solimp=\"" << kTunedSolimp << "\"";
    } else {
      xml << " friction=\"" << mat.friction << " 0.005 0.0001\" solref=\"0.02 " << zeta << "\"";
    }
    xml << "/>\n    </body>\n  </worldbody>\n</mujoco>\n";
    model_xml_ = xml.str();
    load();

    mj_resetData(model_, data_);
    if (s.rotation_frozen) {
      const Eigen::Vector3d& v = s.initial.velocity_world;
      for (int k = 0; k < 3; ++k) {
        data_->qpos[k] = 0.0;
        data_->qvel[k] = v[k];
      }
    } else {
      const Eigen::Quaterniond& q = s.initial.orientation;
      const Eigen::Vector3d& v = s.initial.velocity_world;
      // Free joint: qvel's angular part is in the body frame.
      const Eigen::Vector3d w_body = q.conjugate() * s.initial_omega_world;
      const double qpos[7] = {x.x(), x.y(), x.z(), q.w(), q.x(), q.y(), q.z()};
      const double qvel[6] = {v.x(), v.y(), v.z(), w_body.x(), w_body.y(), w_body.z()};
      for (int k = 0; k < 7; ++k) data_->qpos[k] = qpos[k];
      for (int k = 0; k < 6; ++k) data_->qvel[k] = qvel[k];
    }
    frozen_ = s.rotation_frozen;
    origin_ = x;
    mj_forward(model_, data_);

    const int lens = mj_name2id(model_, mjOBJ_GEOM, "lens");
    const mjtNum* gs = model_->geom_solref + 2 * lens;
    const mjtNum* gi = model_->geom_solimp + 5 * lens;
    const mjtNum* gf = model_->geom_friction + 3 * lens;
    const char* cones[] = {"pyramidal", "elliptic"};
    const char* integrators[] = {"Euler", "RK4", "implicit"};
    settings_ = {
        {"stepping",
         std::string("mj_step, timestep = dt, integrator ") + integrators[model_->opt.integrator] +
             ", solver " + (model_->opt.solver == mjSOL_NEWTON ? "Newton" : "other") + ", " +
             std::to_string(model_->opt.iterations) + " iterations",
         "XML reference, option"},
        {"stone geom",
         "mesh of the lens tessellation (" + std::to_string(model_->mesh_vertnum[0]) +
             " vertices; collisions use its convex hull), explicit <inertial>, " +
             (frozen_ ? "three slide joints" : "free joint"),
         "XML reference, mesh and geom; Computation, Collision detection"},
        {"board, table", "box geom (board), plane geom (table)", "XML reference, geom"},
        {"condim; friction (sliding, torsional m, rolling m)",
         std::to_string(model_->geom_condim[lens]) + "; " + num(gf[0]) + ", " + num(gf[1]) + ", " +
             num(gf[2]),
         "Modeling, Contact parameters; XML reference, geom"},
        {"solref (timeconst s, dampratio)",
         num(gs[0]) + ", " + num(gs[1]) +
             (tuned_ ? " (timeconst = max(2 ms, 2 dt / dampratio))"
                     : " (MuJoCo raises timeconst to 2 dt when smaller: refsafe)"),
         "Modeling, Solver parameters and Restitution"},
        {"solimp (dmin, dmax, width m, midpoint, power)",
         num(gi[0]) + ", " + num(gi[1]) + ", " + num(gi[2]) + ", " + num(gi[3]) + ", " + num(gi[4]),
         "Modeling, Solver parameters"},
        {"friction cone, impratio, noslip iterations",
         std::string(cones[model_->opt.cone]) + ", " + num(model_->opt.impratio) + ", " +
             std::to_string(model_->opt.noslip_iterations),
         "XML reference, option; Modeling, Preventing slip"},
        {"multiccd (several contacts per mesh pair)",
         (model_->opt.enableflags & mjENBL_MULTICCD) ? "enabled" : "disabled",
         "XML reference, option/flag (experimental in 2.2)"},
        {"margin (m), sleeping",
         num(model_->geom_margin[lens]) + ", none (MuJoCo 2.2 has no sleeping)",
         "XML reference, geom"},
    };
  }

  void advance() override { mj_step(model_, data_); }

  ContactSample sample() const override {
    ContactSample smp;
    if (frozen_) {
      const double* p = data_->qpos;
      const double* v = data_->qvel;
      smp.position_world = origin_ + Eigen::Vector3d(p[0], p[1], p[2]);
      smp.velocity_world = Eigen::Vector3d(v[0], v[1], v[2]);
      return smp;
    }
    const double* p = data_->qpos;
    const double* v = data_->qvel;
    const Eigen::Quaterniond q(p[3], p[4], p[5], p[6]);
    smp.position_world = Eigen::Vector3d(p[0], p[1], p[2]);
    smp.orientation = q;
    smp.velocity_world = Eigen::Vector3d(v[0], v[1], v[2]);
    smp.omega_world = q * Eigen::Vector3d(v[3], v[4], v[5]);
    return smp;
  }

  bool asleep() const override { return false; }

  std::string failure() const override {
    if (data_->warning[mjWARN_BADQACC].number > 0) return "diverged (MuJoCo: bad qacc, reset)";
    if (data_->warning[mjWARN_BADQVEL].number > 0) return "diverged (MuJoCo: bad qvel, reset)";
    if (data_->warning[mjWARN_BADQPOS].number > 0) return "diverged (MuJoCo: bad qpos, reset)";
    if (data_->warning[mjWARN_CONTACTFULL].number > 0) return "MuJoCo: contact buffer full";
    return "";
  }
  std::vector<Setting> settings() const override { return settings_; }

 private:
  void load() {
    char path[] = "/tmp/vg_contact_mujoco_XXXXXX.xml";
    const int fd = mkstemps(path, 4);
    if (fd < 0) throw std::runtime_error("cannot create a temporary file for the MuJoCo model");
    const bool written =
        write(fd, model_xml_.data(), model_xml_.size()) == static_cast<ssize_t>(model_xml_.size());
    close(fd);
    char error[1000] = "";
    model_ = written ? mj_loadXML(path, nullptr, error, sizeof error) : nullptr;
    unlink(path);
    if (!model_) throw std::runtime_error(std::string("MuJoCo could not load the model: ") + error);
    data_ = mj_makeData(model_);
  }
  void unload() {
    if (data_) mj_deleteData(data_);
    if (model_) mj_deleteModel(model_);
    data_ = nullptr;
    model_ = nullptr;
  }

  bool tuned_;
  bool frozen_ = false;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  std::string model_xml_;
  std::vector<Setting> settings_;
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
};

}  // namespace

void init_mujoco_messages() {
  // Without a handler MuJoCo prints each warning and appends it to MUJOCO_LOG.TXT; the
  // benchmark reads the counters in mjData::warning instead (MujocoContact::failure()).
  mju_user_warning = [](const char*) {};
}

std::unique_ptr<ContactMethod> make_mujoco_contact(bool tuned) {
  return std::make_unique<MujocoContact>(tuned);
}

}  // namespace vg_bench
