#include "env/arm.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "env/embedded_models.h"

namespace vaegail {

namespace {
const char* const kJointNames[] = {"arm_1", "arm_2", "arm_3", "arm_4", "arm_5",
                                   "arm_6", "finger_1", "finger_2", "finger_3"};

MujocoEnvOptions arm_env_options(const ArmOptions& options) {
  MujocoEnvOptions o;
  o.id = "arm";
  o.frame_skip = 10;  // 0.05 s control step on a 0.005 s physics step
  o.episode_length = options.episode_length;
  o.reset_noise = 0;
  return o;
}
}  // namespace

ArmEnv::ArmEnv(ArmOptions options) : ArmEnv(MujocoModel::from_xml("arm.xml", embedded_model("arm.xml")), options) {}

ArmEnv::ArmEnv(std::shared_ptr<const MujocoModel> model, ArmOptions options)
    : MujocoEnv(std::move(model), arm_env_options(options)), arm_options_(options) {
  const mjModel* m = model_->get();
  if (m->nq != kJoints || m->nv != kJoints || m->nu != kJoints)
    throw std::runtime_error(model_->source() + ": the arm needs 9 hinge joints and 9 actuators");
  grip_ = model_->id(mjOBJ_SITE, "grip");
  obs_spec_.names.clear();
  for (const char* j : kJointNames) obs_spec_.names.push_back(std::string(j) + "_angle");
  for (const char* j : kJointNames) obs_spec_.names.push_back(std::string(j) + "_vel");
  for (const char* c : {"grip_x", "grip_y", "grip_z"}) obs_spec_.names.push_back(c);
  obs_spec_.low.assign(obs_spec_.names.size(), -mjMAXVAL);
  obs_spec_.high.assign(obs_spec_.names.size(), mjMAXVAL);
  feature_names_ = {"grip_x", "grip_y", "grip_z", "target_distance"};
  context_names_ = {"target_x", "target_y", "target_z"};
  context_ = {0.45, 0.0, 0.25};  // the workspace centre
}

std::array<double, 3> ArmEnv::grip_position() const {
  const double* p = data()->site_xpos + 3 * grip_;
  return {p[0], p[1], p[2]};
}

double point_distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  double sq = 0;
  for (int k = 0; k < 3; ++k) sq += (a[k] - b[k]) * (a[k] - b[k]);
  return std::sqrt(sq);
}

double ArmEnv::target_distance() const {
  return point_distance(grip_position(), {context_[0], context_[1], context_[2]});
}

void ArmEnv::observe(float* out) const {
  const mjData* d = data();
  for (int j = 0; j < kJoints; ++j) {
    out[j] = static_cast<float>(d->qpos[j]);
    out[kJoints + j] = static_cast<float>(d->qvel[j]);
  }
  const auto g = grip_position();
  for (int k = 0; k < 3; ++k) out[2 * kJoints + k] = static_cast<float>(g[k]);
}

void ArmEnv::features(double* out) const {
  const auto g = grip_position();
  for (int k = 0; k < 3; ++k) out[k] = g[k];
  out[3] = target_distance();
}

std::vector<double> ArmEnv::random_target(Rng& rng) {
  std::vector<double> target(3);
  for (int k = 0; k < 3; ++k) target[k] = rng.uniform(kTargetLow[k], kTargetHigh[k]);
  return target;
}

double ArmEnv::task_reward(double target_distance) {
  return 0.5 * std::max(0.0, 1.0 - target_distance) +
         0.5 * std::exp(-(target_distance / 0.05) * (target_distance / 0.05));
}

StepOutcome ArmEnv::step(const float* action) {
  std::copy(data()->qpos, data()->qpos + kJoints, angles_at_command_.begin());
  return MujocoEnv::step(action);
}

double ArmEnv::command_jump() const {
  const double* applied = data()->ctrl;  // the commands after clipping to the joint ranges
  double sq = 0;
  for (int j = 0; j < kJoints; ++j) sq += (applied[j] - angles_at_command_[j]) * (applied[j] - angles_at_command_[j]);
  return sq / kJoints;
}

double ArmEnv::reward(const float*) const {
  return task_reward(target_distance()) - arm_options_.command_cost * command_jump() - posture_charge();
}

double ArmEnv::posture_charge() const {
  double sq = 0;
  for (int j = 0; j < kJoints; ++j) sq += data()->qpos[j] * data()->qpos[j];
  return arm_options_.posture_cost * sq / kJoints;
}

void ArmEnv::initialize_episode(Rng&) {}  // the home pose: mj_resetData's qpos0 and zero velocity

std::unique_ptr<Env> ArmEnv::clone() const {
  auto copy = std::make_unique<ArmEnv>(model_, arm_options_);
  copy->set_context(context_);
  return copy;
}

}  // namespace vaegail
