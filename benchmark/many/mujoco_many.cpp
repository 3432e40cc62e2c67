// MuJoCo with many stones: the contact benchmark's tuned model (contact/mujoco_contact.cpp,
// "tuned for the stone" after MuJoCo's Modeling chapter and XML reference), one body with a
// free joint and a mesh geom per stone (one mesh asset per colour), mj_step with timestep = dt.
// Every stone geom has priority 1 and the same contact parameters, so a stone-stone pair gets
// them as they are (equal priorities mix equal values) and a stone-board pair takes the stone's.
// MuJoCo 2.2.2 (Debian 12) has no sleeping: every stone is integrated at every step.
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <sstream>

#include "../contact/settings_format.h"
#include "many_method.h"

namespace vg_bench {
namespace {

// The contact benchmark's tuned mapping (contact/mujoco_contact.cpp): a dampratio giving the
// restitution of a linear damped spring, a timeconst of max(2 ms, 2 dt / dampratio), a constant
// impedance 0.99.
double damping_ratio_for_restitution(double e) {
  if (e <= 0.0) return 1.0;
  const double l = std::log(e);
  return -l / std::sqrt(M_PI * M_PI + l * l);
}
double tuned_timeconst(double dt, double zeta) { return std::max(0.002, 2.0 * dt / zeta); }
constexpr const char* kTunedSolimp = "0.99 0.99 0.001 0.5 2";

class MujocoMany : public ManyMethod {
 public:
  ~MujocoMany() override { unload(); }
  std::string name() const override { return "mujoco"; }
  bool has_sleep() const override { return false; }
  std::string version() const override {
    const int v = mj_version();
    return "MuJoCo " + std::to_string(v / 100) + "." + std::to_string(v / 10 % 10) + "." +
           std::to_string(v % 10) + " (Debian libmujoco-dev)";
  }

  void reset(const ManyScene& s, double dt) override {
    unload();
    const SurfaceMaterial& mat = s.material;
    const double zeta = damping_ratio_for_restitution(mat.restitution);
    const std::size_t n = s.stones.size();
    // MuJoCo 2.2 allocates njmax x njmax matrices (efc_AR): the buffers are sized to what the
    // scenes use (a resting stone makes one contact, 6 rows with condim 6) with room for twice
    // that; a full buffer is reported as a failure.
    const long ncon = 2 * static_cast<long>(n) + 32;
    std::ostringstream xml;
    xml.precision(17);
    const Eigen::Vector3d& g = s.gravity_world;
    xml << "<mujoco model=\"stones\">\n"
        << "  <option timestep=\"" << dt << "\" gravity=\"" << g.x() << " " << g.y() << " " << g.z()
        << "\" cone=\"elliptic\" noslip_iterations=\"10\">\n"
        << "    <flag multiccd=\"enable\"/>\n  </option>\n"
        << "  <size nconmax=\"" << ncon << "\" njmax=\"" << 6 * ncon << "\"/>\n  <asset>\n";
    for (const Colour c : {Colour::black, Colour::white}) {
      xml << "    <mesh name=\"" << (c == Colour::black ? "black" : "white") << "\" vertex=\"";
      for (const Eigen::Vector3d& v :
           make_lens_hull(c == Colour::black ? s.black : s.white).vertices_body)
        xml << v.x() << " " << v.y() << " " << v.z() << " ";
      xml << "\"/>\n";
    }
    xml << "  </asset>\n  <worldbody>\n";
    if (s.board_enabled) {
      const Eigen::Vector3d half = s.board.half_extent_m(), centre = s.board.centre_world();
      xml << "    <geom name=\"table\" type=\"plane\" size=\"0 0 1\" pos=\"0 0 "
          << s.board.table_z_m() << "\"/>\n"
          << "    <geom name=\"board\" type=\"box\" size=\"" << half.x() << " " << half.y() << " "
          << half.z() << "\" pos=\"" << centre.x() << " " << centre.y() << " " << centre.z()
          << "\"/>\n";
    }
    for (std::size_t i = 0; i < n; ++i) {
      const StoneSpec& spec = s.spec(i);
      const Eigen::Vector3d& in = spec.principal_moments_body;
      const char* mesh = s.stones[i].colour == Colour::black ? "black" : "white";
      xml << "    <body name=\"s" << i << "\">\n      <freejoint/>\n"
          << "      <inertial pos=\"0 0 0\" mass=\"" << spec.mass_kg << "\" diaginertia=\""
          << in.x() << " " << in.y() << " " << in.z() << "\"/>\n"
          << "      <geom type=\"mesh\" mesh=\"" << mesh << "\" priority=\"1\" condim=\"6\""
          << " friction=\"" << mat.friction << " " << mat.spinning_friction_m << " "
          << mat.rolling_resistance_m << "\" solref=\"" << tuned_timeconst(dt, zeta) << " " << zeta
          << "\" solimp=\"" << kTunedSolimp << "\"/>\n    </body>\n";
    }
    xml << "  </worldbody>\n</mujoco>\n";
    load(xml.str());

    mj_resetData(model_, data_);
    for (std::size_t i = 0; i < n; ++i) {
      const ManyStone& st = s.stones[i];
      const Eigen::Vector3d& x = st.initial.position_world;
      const Eigen::Quaterniond& q = st.initial.orientation;
      const Eigen::Vector3d& v = st.initial.velocity_world;
      const Eigen::Vector3d w_body = q.conjugate() * st.omega_world;  // free joint: body frame
      const double qpos[7] = {x.x(), x.y(), x.z(), q.w(), q.x(), q.y(), q.z()};
      const double qvel[6] = {v.x(), v.y(), v.z(), w_body.x(), w_body.y(), w_body.z()};
      for (int k = 0; k < 7; ++k) data_->qpos[7 * i + k] = qpos[k];
      for (int k = 0; k < 6; ++k) data_->qvel[6 * i + k] = qvel[k];
    }
    mj_forward(model_, data_);

    const int geom = s.board_enabled ? 2 : 0;  // the first stone's geom
    const mjtNum* gs = model_->geom_solref + 2 * geom;
    settings_ = {
        {"stepping",
         "mj_step, timestep = dt, Euler, Newton solver, " + std::to_string(model_->opt.iterations) +
             " iterations; elliptic cones, noslip " +
             std::to_string(model_->opt.noslip_iterations) + " iterations; multiccd",
         "XML reference, option"},
        {"stone geoms",
         "one mesh per colour (" + std::to_string(model_->mesh_vertnum[0]) +
             " vertices, collided as its convex hull), a free joint and explicit <inertial> "
             "per stone; nconmax " +
             std::to_string(model_->nconmax) + ", njmax " + std::to_string(model_->njmax),
         "XML reference, mesh, geom, size"},
        {"condim; friction (sliding, torsional m, rolling m)",
         std::to_string(model_->geom_condim[geom]) + "; " + num(mat.friction) + ", " +
             num(mat.spinning_friction_m) + ", " + num(mat.rolling_resistance_m),
         "Modeling, Contact parameters"},
        {"solref (timeconst s, dampratio); solimp",
         num(gs[0]) + ", " + num(gs[1]) + "; " + kTunedSolimp,
         "Modeling, Solver parameters and Restitution"},
        {"sleeping", "none: MuJoCo 2.2.2 has no sleeping (no such option or flag in mjModel)",
         "XML reference, option"},
    };
  }

  void advance() override { mj_step(model_, data_); }

  ContactSample sample(std::size_t i) const override {
    const double* p = data_->qpos + 7 * i;
    const double* v = data_->qvel + 6 * i;
    const Eigen::Quaterniond q(p[3], p[4], p[5], p[6]);
    ContactSample smp;
    smp.position_world = Eigen::Vector3d(p[0], p[1], p[2]);
    smp.orientation = q;
    smp.velocity_world = Eigen::Vector3d(v[0], v[1], v[2]);
    smp.omega_world = q * Eigen::Vector3d(v[3], v[4], v[5]);
    return smp;
  }
  bool asleep(std::size_t) const override { return false; }
  std::string failure() const override {
    if (data_->warning[mjWARN_BADQACC].number > 0) return "diverged (MuJoCo: bad qacc, reset)";
    if (data_->warning[mjWARN_CONTACTFULL].number > 0) return "MuJoCo: contact buffer full";
    if (data_->warning[mjWARN_CNSTRFULL].number > 0) return "MuJoCo: constraint buffer full";
    return "";
  }
  std::vector<Setting> settings() const override { return settings_; }

 private:
  void load(const std::string& text) {
    char path[] = "/tmp/vg_many_mujoco_XXXXXX.xml";
    const int fd = mkstemps(path, 4);
    if (fd < 0) throw std::runtime_error("cannot create a temporary file for the MuJoCo model");
    const bool written = write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
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

  std::vector<Setting> settings_;
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
};

}  // namespace

void init_mujoco_many_messages() {
  mju_user_warning = [](const char*) {};
}

std::unique_ptr<ManyMethod> make_mujoco_many() { return std::make_unique<MujocoMany>(); }

}  // namespace vg_bench
