#include "env/walker.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "env/embedded_models.h"
#include "env/reward_terms.h"

namespace vaegail {

namespace {
const char* const kJoints[] = {"right_hip", "right_knee", "right_ankle",
                               "left_hip",  "left_knee",  "left_ankle"};
constexpr int kWalkerRootDofs = 3;  // rootx, rootz, rooty come first in qpos and qvel

MujocoEnvOptions walker_env_options(const WalkerOptions& options) {
  MujocoEnvOptions o;
  o.id = "walker";
  o.frame_skip = 10;  // 0.025 s control step on a 0.0025 s physics step
  o.episode_length = options.episode_length;
  return o;
}
}  // namespace

WalkerEnv::WalkerEnv(WalkerOptions options)
    : WalkerEnv(MujocoModel::from_xml("walker.xml", embedded_model("walker.xml")), options) {}

WalkerEnv::WalkerEnv(std::shared_ptr<const MujocoModel> model, WalkerOptions options)
    : MujocoEnv(std::move(model), walker_env_options(options)), walker_options_(options) {
  torso_ = model_->id(mjOBJ_BODY, "torso");
  obs_spec_.names = {"torso_height", "torso_pitch_sin", "torso_pitch_cos"};
  for (const char* j : kJoints) obs_spec_.names.push_back(std::string(j) + "_angle");
  for (const char* r : {"rootx_vel", "rootz_vel", "rooty_vel"}) obs_spec_.names.push_back(r);
  for (const char* j : kJoints) obs_spec_.names.push_back(std::string(j) + "_vel");
  obs_spec_.low.assign(obs_spec_.names.size(), -mjMAXVAL);
  obs_spec_.high.assign(obs_spec_.names.size(), mjMAXVAL);
  feature_names_ = {"com_speed", "torso_height", "fallen"};
  context_names_ = {"target_speed"};
  context_ = {0.0};
  const mjModel* m = model_->get();
  if (m->nq != kWalkerRootDofs + 6 || m->nv != kWalkerRootDofs + 6 || m->nu != 6)
    throw std::runtime_error(model_->source() + ": walker needs 9 joints and 6 actuators");
}

double WalkerEnv::torso_height() const { return data()->xpos[3 * torso_ + 2]; }
double WalkerEnv::torso_pitch() const { return data()->qpos[2]; }

double WalkerEnv::com_speed() const {
  double v[3];
  subtree_velocity(torso_, v);
  return v[0];
}

bool WalkerEnv::fallen() const {
  return torso_height() < kFallHeight || std::cos(torso_pitch()) < kFallCosPitch;
}

void WalkerEnv::observe(float* out) const {
  const mjData* d = data();
  const double pitch = torso_pitch();
  out[0] = static_cast<float>(torso_height());
  out[1] = static_cast<float>(std::sin(pitch));
  out[2] = static_cast<float>(std::cos(pitch));
  for (int j = 0; j < 6; ++j) out[3 + j] = static_cast<float>(d->qpos[kWalkerRootDofs + j]);
  for (int k = 0; k < 9; ++k) out[9 + k] = static_cast<float>(d->qvel[k]);
}

void WalkerEnv::features(double* out) const {
  out[0] = com_speed();
  out[1] = torso_height();
  out[2] = fallen() ? 1.0 : 0.0;
}

double WalkerEnv::task_reward(double com_speed, double target_speed, double torso_height,
                              double pitch, const float* action, int act_dim) {
  const double stand = std::clamp((torso_height - 0.8) / 0.4, 0.0, 1.0);
  const double upright = 0.5 * (1.0 + std::cos(pitch));
  // A linear term whose slope reaches back to standing still even for 3 m/s (a Gaussian alone
  // gives a 3 m/s learner no signal at rest), plus a sharp one for precision near the target.
  const double dv = std::abs(com_speed - target_speed);
  const double move = 0.6 * std::max(0.0, 1.0 - dv / std::max(1.0, std::abs(target_speed))) +
                      0.4 * std::exp(-2.0 * dv * dv);
  // Being up pays on its own: otherwise a learner far from its target speed earns less than the
  // effort it spends and learns to fall at once, ending the episode.
  return stand * upright * (kAliveWeight + (1.0 - kAliveWeight) * move) - effort_charge(0.05, action, act_dim);
}

double WalkerEnv::reward(const float* action) const {
  return task_reward(com_speed(), context_[0], torso_height(), torso_pitch(), action, 6) - posture_charge();
}

double WalkerEnv::posture_charge() const {
  double sq = 0;
  for (int j = 0; j < 6; ++j) sq += data()->qpos[kWalkerRootDofs + j] * data()->qpos[kWalkerRootDofs + j];
  return walker_options_.posture_cost * sq / 6;
}

bool WalkerEnv::has_terminated() const { return walker_options_.terminate_on_fall && fallen(); }

void WalkerEnv::initialize_episode(Rng& rng) {
  const mjModel* m = model();
  mjData* d = mutable_data();
  d->qpos[2] = rng.uniform(-0.05, 0.05);
  for (int j = 0; j < 6; ++j) {
    const int q = kWalkerRootDofs + j;
    const int joint = m->dof_jntid[q];
    d->qpos[q] = std::clamp(rng.uniform(-0.1, 0.1), m->jnt_range[2 * joint], m->jnt_range[2 * joint + 1]);
  }
  for (int k = 0; k < 9; ++k) d->qvel[k] = rng.uniform(-0.05, 0.05);
}

std::unique_ptr<Env> WalkerEnv::clone() const {
  auto copy = std::make_unique<WalkerEnv>(model_, walker_options_);
  copy->set_context(context_);
  return copy;
}

}  // namespace vaegail
