#include "env/humanoid.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "env/embedded_models.h"
#include "env/reward_terms.h"

namespace vaegail {

namespace {
constexpr int kRootQpos = 7;  // the free root's position and quaternion come first in qpos
constexpr int kHumanoidRootDofs = 6;  // and its linear and angular velocity first in qvel

MujocoEnvOptions humanoid_env_options(const HumanoidOptions& options) {
  MujocoEnvOptions o;
  o.id = "humanoid";
  o.frame_skip = 6;  // 0.03 s control step on a 0.005 s physics step
  o.episode_length = options.episode_length;
  o.reset_noise = 0.02;  // the base's seeded perturbation of every hinge around the rest pose
  return o;
}

// 1 / (1 + ((x - target) / scale)^2): 1 on target, 1/2 at a miss of `scale`, and a slope left far
// off, where a Gaussian's is gone.
double credit(double x, double target, double scale) {
  const double miss = (x - target) / scale;
  return 1.0 / (1.0 + miss * miss);
}
}  // namespace

HumanoidEnv::HumanoidEnv(HumanoidOptions options)
    : HumanoidEnv(MujocoModel::from_xml("humanoid_cmu.xml", embedded_model("humanoid_cmu.xml")), options) {}

HumanoidEnv::HumanoidEnv(std::shared_ptr<const MujocoModel> model, HumanoidOptions options)
    : MujocoEnv(std::move(model), humanoid_env_options(options)), humanoid_options_(options) {
  const mjModel* m = model_->get();
  if (m->nq != kRootQpos + kHinges || m->nv != kHumanoidRootDofs + kHinges || m->nu != kHinges ||
      m->jnt_type[0] != mjJNT_FREE)
    throw std::runtime_error(model_->source() + ": the humanoid needs a free root, 56 hinges and 56 motors");
  root_ = model_->id(mjOBJ_BODY, "root");
  head_ = model_->id(mjOBJ_BODY, "head");
  floor_ = model_->id(mjOBJ_GEOM, "floor");
  for (std::size_t k = 0; k < kEndEffectors.size(); ++k) end_effectors_[k] = model_->id(mjOBJ_BODY, kEndEffectors[k]);
  const char* const feet[] = {"lfoot", "ltoes", "rfoot", "rtoes"};
  for (int k = 0; k < 4; ++k) feet_[k] = model_->id(mjOBJ_BODY, feet[k]);

  obs_spec_.names.clear();
  for (const char* suffix : {"_angle", "_vel"})
    for (int j = 1; j <= kHinges; ++j) obs_spec_.names.push_back(mj_id2name(m, mjOBJ_JOINT, j) + std::string(suffix));
  std::vector<std::string> effector_names;
  for (const char* body : kEndEffectors)
    for (const char* axis : {"_x", "_y", "_z"}) effector_names.push_back(body + std::string(axis));
  for (const char* n : {"root_height", "up_x", "up_y", "up_z", "root_vel_x", "root_vel_y", "root_vel_z",
                        "root_angvel_x", "root_angvel_y", "root_angvel_z"})
    obs_spec_.names.push_back(n);
  obs_spec_.names.insert(obs_spec_.names.end(), effector_names.begin(), effector_names.end());
  obs_spec_.low.assign(obs_spec_.names.size(), -mjMAXVAL);
  obs_spec_.high.assign(obs_spec_.names.size(), mjMAXVAL);
  feature_names_ = {"forward_speed", "heading", "root_height", "fallen"};
  feature_names_.insert(feature_names_.end(), effector_names.begin(), effector_names.end());
  context_names_ = {"style"};
  context_ = {0.0};
}

std::array<double, 3> HumanoidEnv::to_root_frame(const double* world) const {
  const double* r = data()->xmat + 9 * root_;  // row-major, root-frame axes as columns
  return {r[0] * world[0] + r[3] * world[1] + r[6] * world[2],
          r[1] * world[0] + r[4] * world[1] + r[7] * world[2],
          r[2] * world[0] + r[5] * world[1] + r[8] * world[2]};
}

double HumanoidEnv::root_height() const { return data()->xpos[3 * root_ + 2]; }

std::array<double, 3> HumanoidEnv::up_in_root() const {
  const double up[3] = {0, 0, 1};
  return to_root_frame(up);
}

double HumanoidEnv::heading() const {
  const double* r = data()->xmat + 9 * root_;
  return std::atan2(r[3], r[0]);
}

double HumanoidEnv::forward_speed() const {
  double v[3];
  subtree_velocity(root_, v);  // the root's subtree is the whole body
  const double h = heading();
  return v[0] * std::cos(h) + v[1] * std::sin(h);
}

std::array<double, 3> HumanoidEnv::end_effector(int k) const {
  const double* p = data()->xpos + 3 * end_effectors_[k];
  const double* root = data()->xpos + 3 * root_;
  const double offset[3] = {p[0] - root[0], p[1] - root[1], p[2] - root[2]};
  return to_root_frame(offset);
}

bool HumanoidEnv::off_feet_contact() const {
  const mjModel* m = model();
  const mjData* d = data();
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    if (c.geom1 != floor_ && c.geom2 != floor_) continue;
    const int body = m->geom_bodyid[c.geom1 == floor_ ? c.geom2 : c.geom1];
    if (std::find(feet_.begin(), feet_.end(), body) == feet_.end()) return true;
  }
  return false;
}

bool HumanoidEnv::fallen() const {
  return data()->xpos[3 * head_ + 2] < kFallHeadHeight || root_height() < kFallRootHeight || off_feet_contact();
}

void HumanoidEnv::observe(float* out) const {
  const mjData* d = data();
  for (int j = 0; j < kHinges; ++j) {
    out[j] = static_cast<float>(d->qpos[kRootQpos + j]);
    out[kHinges + j] = static_cast<float>(d->qvel[kHumanoidRootDofs + j]);
  }
  float* o = out + 2 * kHinges;
  *o++ = static_cast<float>(root_height());
  // The free joint's linear velocity is in the world frame, its angular velocity in the body's.
  for (const auto& v : {up_in_root(), to_root_frame(d->qvel)})
    for (double x : v) *o++ = static_cast<float>(x);
  for (int k = 3; k < 6; ++k) *o++ = static_cast<float>(d->qvel[k]);
  for (std::size_t e = 0; e < kEndEffectors.size(); ++e)
    for (double x : end_effector(static_cast<int>(e))) *o++ = static_cast<float>(x);
}

void HumanoidEnv::features(double* out) const {
  *out++ = forward_speed();
  *out++ = heading();
  *out++ = root_height();
  *out++ = fallen() ? 1.0 : 0.0;
  for (std::size_t e = 0; e < kEndEffectors.size(); ++e)
    for (double x : end_effector(static_cast<int>(e))) *out++ = x;
}

double HumanoidEnv::yaw_rate() const {
  // The free joint's angular velocity is in the root frame; its world z is the xmat's third row.
  const double* r = data()->xmat + 9 * root_;
  const double* w = data()->qvel + 3;
  return r[6] * w[0] + r[7] * w[1] + r[8] * w[2];
}

double HumanoidEnv::lateral_speed() const {
  double v[3];
  subtree_velocity(root_, v);
  const double h = heading();
  return -v[0] * std::sin(h) + v[1] * std::cos(h);
}

StyleTerms HumanoidEnv::style_measures() const {
  const auto lhand = end_effector(0), rhand = end_effector(1), lfoot = end_effector(2), rfoot = end_effector(3);
  StyleTerms m{};
  m[kForwardSpeed] = forward_speed();
  m[kSwaySpeed] = std::abs(lateral_speed());
  m[kTurnRate] = std::abs(yaw_rate());
  m[kRootHeight] = root_height();
  m[kHeadForward] = end_effector(4)[0];
  m[kHandHeight] = 0.5 * (lhand[2] + rhand[2]);
  m[kHandSpread] = 0.5 * (std::abs(lhand[1]) + std::abs(rhand[1]));
  m[kFootSpread] = 0.5 * (std::abs(lfoot[1]) + std::abs(rfoot[1]));
  return m;
}

double HumanoidEnv::upright_forward_reward(double forward_speed, double up_z, const float* action, int act_dim) {
  const double upright = 0.5 * (1.0 + up_z);
  const double moving = credit(forward_speed, kTargetSpeed, kSpeedScale);
  return upright * (kAliveWeight + (1.0 - kAliveWeight) * moving) - effort_charge(0.05, action, act_dim);
}

// The label is only a name: neither the dynamics nor the reward reads it. One that is no index
// (negative, fractional, not finite) can only come from a corrupt or foreign file, refused where it
// first meets the environment; MujocoEnv refuses a context of another size.
void HumanoidEnv::set_context(const std::vector<double>& context) {
  if (context.size() == 1 && !(std::isfinite(context[0]) && context[0] >= 0 && context[0] == std::floor(context[0]))) {
    std::ostringstream message;
    message << "humanoid: style " << context[0] << " is no style label (a non-negative integer)";
    throw std::invalid_argument(message.str());
  }
  MujocoEnv::set_context(context);
}

std::vector<int> HumanoidEnv::discriminator_observation() const {
  std::vector<int> indices;
  for (int i = 2 * kHinges; i < obs_dim(); ++i) indices.push_back(i);  // after the angles and velocities
  return indices;
}

double HumanoidEnv::reward(const float* action) const {
  return upright_forward_reward(forward_speed(), up_in_root()[2], action, kHinges);
}

bool HumanoidEnv::has_terminated() const { return humanoid_options_.terminate_on_fall && fallen(); }

std::unique_ptr<Env> HumanoidEnv::clone() const {
  auto copy = std::make_unique<HumanoidEnv>(model_, humanoid_options_);
  copy->set_context(context_);
  return copy;
}

}  // namespace vaegail
