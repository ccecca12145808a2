#include "env/mujoco_env.h"

#include <algorithm>
#include <stdexcept>

namespace vaegail {

namespace {
std::string object_name(const mjModel* m, mjtObj type, int i, const char* fallback) {
  const char* name = mj_id2name(m, type, i);
  return name && *name ? name : fallback + std::to_string(i);
}
}  // namespace

MujocoEnv::MujocoEnv(std::shared_ptr<const MujocoModel> model, MujocoEnvOptions options)
    : model_(std::move(model)), options_(std::move(options)), data_(mj_makeData(model_->get())) {
  if (options_.frame_skip < 1) throw std::invalid_argument("frame_skip must be at least 1");
  if (options_.episode_length < 1) throw std::invalid_argument("episode_length must be at least 1");
  const mjModel* m = model_->get();
  if (!data_) throw std::runtime_error(model_->source() + ": cannot allocate simulation data");
  for (int j = 0; j < m->njnt; ++j) {
    const std::string joint = object_name(m, mjOBJ_JOINT, j, "joint");
    const int width = m->jnt_type[j] == mjJNT_FREE ? 7 : m->jnt_type[j] == mjJNT_BALL ? 4 : 1;
    for (int k = 0; k < width; ++k)
      obs_spec_.names.push_back("qpos:" + joint + (width > 1 ? "[" + std::to_string(k) + "]" : ""));
  }
  for (int j = 0; j < m->njnt; ++j) {
    const std::string joint = object_name(m, mjOBJ_JOINT, j, "joint");
    const int width = m->jnt_type[j] == mjJNT_FREE ? 6 : m->jnt_type[j] == mjJNT_BALL ? 3 : 1;
    for (int k = 0; k < width; ++k)
      obs_spec_.names.push_back("qvel:" + joint + (width > 1 ? "[" + std::to_string(k) + "]" : ""));
  }
  obs_spec_.low.assign(obs_spec_.names.size(), -mjMAXVAL);
  obs_spec_.high.assign(obs_spec_.names.size(), mjMAXVAL);
  for (int a = 0; a < m->nu; ++a) {
    act_spec_.names.push_back(object_name(m, mjOBJ_ACTUATOR, a, "actuator"));
    const bool limited = m->actuator_ctrllimited[a];
    act_spec_.low.push_back(limited ? m->actuator_ctrlrange[2 * a] : -1.0);
    act_spec_.high.push_back(limited ? m->actuator_ctrlrange[2 * a + 1] : 1.0);
  }
  feature_names_ = {"com_speed_x"};
}

double MujocoEnv::control_timestep() const { return model_->get()->opt.timestep * options_.frame_skip; }

void MujocoEnv::set_context(const std::vector<double>& context) {
  if (context.size() != context_names_.size())
    throw std::invalid_argument(id() + ": context has " + std::to_string(context.size()) +
                                " values, expected " + std::to_string(context_names_.size()));
  context_ = context;
}

void MujocoEnv::reset(std::uint64_t seed) {
  mj_resetData(model_->get(), data_.get());
  Rng rng(seed);
  initialize_episode(rng);
  mj_forward(model_->get(), data_.get());
  steps_ = 0;
}

void MujocoEnv::initialize_episode(Rng& rng) {
  const mjModel* m = model_->get();
  mjData* d = data_.get();
  const double noise = options_.reset_noise;
  for (int j = 0; j < m->njnt; ++j) {
    if (m->jnt_type[j] == mjJNT_FREE || m->jnt_type[j] == mjJNT_BALL) continue;
    d->qpos[m->jnt_qposadr[j]] += rng.uniform(-noise, noise);
    d->qvel[m->jnt_dofadr[j]] += rng.uniform(-noise, noise);
  }
}

StepOutcome MujocoEnv::step(const float* action) {
  const mjModel* m = model_->get();
  mjData* d = data_.get();
  for (int a = 0; a < m->nu; ++a)
    d->ctrl[a] = std::clamp(static_cast<double>(action[a]), act_spec_.low[a], act_spec_.high[a]);
  for (int k = 0; k < options_.frame_skip; ++k) mj_step(m, d);
  return finish_step(action);
}

void MujocoEnv::run_controlled(mjData* d, PhysicsStepController& controller, float* mean_action) const {
  const mjModel* m = model_->get();
  if (m->opt.integrator == mjINT_RK4)
    throw std::invalid_argument(model_->source() + ": a controller acting at the physics step needs the Euler or implicit integrator, not RK4");
  std::vector<double> ctrl_sum(m->nu, 0.0);
  for (int k = 0; k < options_.frame_skip; ++k) {
    mj_step1(m, d);
    controller.control(m, d);
    for (int a = 0; a < m->nu; ++a) {
      d->ctrl[a] = std::clamp(d->ctrl[a], act_spec_.low[a], act_spec_.high[a]);
      ctrl_sum[a] += d->ctrl[a];
    }
    mj_step2(m, d);
  }
  for (int a = 0; a < m->nu; ++a) mean_action[a] = static_cast<float>(ctrl_sum[a] / options_.frame_skip);
}

StepOutcome MujocoEnv::step_controlled(PhysicsStepController& controller, float* mean_action) {
  run_controlled(data_.get(), controller, mean_action);
  return finish_step(mean_action);
}

void MujocoEnv::lookahead_controlled(PhysicsStepController& controller, float* mean_action) const {
  const mjModel* m = model_->get();
  if (!lookahead_data_) lookahead_data_.reset(mj_makeData(m));
  mj_copyData(lookahead_data_.get(), m, data_.get());
  run_controlled(lookahead_data_.get(), controller, mean_action);
}

StepOutcome MujocoEnv::finish_step(const float* action) {
  const mjModel* m = model_->get();
  mjData* d = data_.get();
  // mj_step leaves positions and velocities of the new state but kinematic quantities of the
  // old one; refresh those that features and rewards read (cheaper than a full mj_forward).
  mj_kinematics(m, d);
  mj_comPos(m, d);
  mj_comVel(m, d);
  ++steps_;
  StepOutcome out;
  out.reward = reward(action);
  out.terminated = has_terminated();
  out.truncated = !out.terminated && steps_ >= options_.episode_length;
  return out;
}

double MujocoEnv::reward(const float*) const { return 0.0; }

void MujocoEnv::set_state(const mjModel* model, const mjData* data) {
  const mjModel* m = model_->get();
  if (model->nq != m->nq || model->nv != m->nv || model->na != m->na || model->nu != m->nu)
    throw std::invalid_argument(model_->source() + ": the simulation's model has nq/nv/na/nu " +
                                std::to_string(model->nq) + "/" + std::to_string(model->nv) + "/" +
                                std::to_string(model->na) + "/" + std::to_string(model->nu) + ", this one " +
                                std::to_string(m->nq) + "/" + std::to_string(m->nv) + "/" +
                                std::to_string(m->na) + "/" + std::to_string(m->nu));
  mjData* d = data_.get();
  std::copy_n(data->qpos, m->nq, d->qpos);
  std::copy_n(data->qvel, m->nv, d->qvel);
  std::copy_n(data->act, m->na, d->act);
  d->time = data->time;
  mj_forward(m, d);
}

void MujocoEnv::observe(float* out) const {
  const mjModel* m = model_->get();
  const mjData* d = data_.get();
  for (int i = 0; i < m->nq; ++i) out[i] = static_cast<float>(d->qpos[i]);
  for (int i = 0; i < m->nv; ++i) out[m->nq + i] = static_cast<float>(d->qvel[i]);
}

void MujocoEnv::subtree_velocity(int body, double out[3]) const {
  mjData* d = data_.get();  // mj_subtreeVel only fills derived fields
  mj_subtreeVel(model_->get(), d);
  for (int k = 0; k < 3; ++k) out[k] = d->subtree_linvel[3 * body + k];
}

void MujocoEnv::features(double* out) const {
  double v[3];
  subtree_velocity(model_->get()->nbody > 1 ? 1 : 0, v);
  out[0] = v[0];
}

std::unique_ptr<Env> MujocoEnv::clone() const {
  auto copy = std::make_unique<MujocoEnv>(model_, options_);
  copy->set_context(context_);
  return copy;
}

}  // namespace vaegail
