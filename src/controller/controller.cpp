#include "vaegail/controller.h"

#include <torch/torch.h>

#include <stdexcept>

#include "env/mujoco_env.h"
#include "env/registry.h"
#include "gail/bc_agent.h"
#include "gail/gail_agent.h"
#include "gail/run_dir.h"
#include "vae/trained_vae.h"

namespace vaegail {

struct Controller::Impl {
  std::unique_ptr<Env> env;        // the training task: sizes, control step, observe()
  vae::TrajectoryVae vae{nullptr};  // its encoder embeds; null without a latent
  vae::LatentPolicy policy;        // the trainer's own mean policy
};

namespace {

std::unique_ptr<Env> task_env(const std::string& task) {
  EnvRequest request;
  request.task = task;
  return make_env(request);
}

void check_vae_sizes(const std::string& vae_checkpoint, const vae::TrajectoryVae& model, const Env& env) {
  const auto& c = model->config();
  if (c.state_dim != env.obs_dim() || c.action_dim != env.act_dim())
    throw std::invalid_argument(vae_checkpoint + ": the VAE's states/actions have " + std::to_string(c.state_dim) +
                                "/" + std::to_string(c.action_dim) + " components, task '" + env.id() + "' " +
                                std::to_string(env.obs_dim()) + "/" + std::to_string(env.act_dim()));
}

vae::TrajectoryVae load_vae_for(const std::string& vae_checkpoint, const Env& env) {
  auto model = vae::load_trained_vae(vae_checkpoint);
  model->eval();
  check_vae_sizes(vae_checkpoint, model, env);
  return model;
}

void check_size(const char* what, size_t size, size_t expected) {
  if (size != expected)
    throw std::invalid_argument(std::string("Controller: ") + what + " has " + std::to_string(size) +
                                " values, the policy takes " + std::to_string(expected));
}

// A float tensor of `shape` holding a copy of `values`.
torch::Tensor tensor_of(const std::vector<float>& values, torch::IntArrayRef shape) {
  return torch::tensor(torch::ArrayRef<float>(values), torch::kFloat32).view(shape);
}

std::vector<float> to_vector(const torch::Tensor& t) {
  const auto flat = t.to(torch::kCPU, torch::kFloat32).contiguous().view({-1});
  return {flat.data_ptr<float>(), flat.data_ptr<float>() + flat.numel()};
}

}  // namespace

Controller::Controller(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Controller::Controller(Controller&&) noexcept = default;
Controller& Controller::operator=(Controller&&) noexcept = default;
Controller::~Controller() = default;

Controller Controller::load_vae(const std::string& vae_run, const std::string& task) {
  auto impl = std::make_unique<Impl>();
  impl->env = task_env(task);
  impl->vae = load_vae_for(vae_run, *impl->env);
  impl->policy = vae::vae_mean_policy(impl->vae, torch::kCPU);
  return Controller(std::move(impl));
}

Controller Controller::load_gail(const std::string& run, const std::string& task,
                                 const std::string& vae_checkpoint) {
  auto impl = std::make_unique<Impl>();
  impl->env = task_env(task);
  const RunFile file = open_run(run, "gail");
  const auto options = run_options<GailOptions>(file);
  // A weights file sizes its VAE itself; a trainer checkpoint needs the VAE's own file for that.
  impl->vae = recorded_vae(file);
  if (options.mode == GailMode::Diverse && impl->vae.is_empty())
    impl->vae = load_vae_for(vae_checkpoint.empty() ? options.vae_path : vae_checkpoint, *impl->env);
  else if (!impl->vae.is_empty())
    check_vae_sizes(file.path, impl->vae, *impl->env);
  // The agent's weights hold the frozen VAE too: loading them sets the encoder's weights to the
  // run's own.
  const auto agent = load_gail_agent(file.path, impl->env->obs_dim(), impl->env->act_dim(), impl->vae, torch::kCPU);
  impl->policy = agent_mean_policy(agent);
  return Controller(std::move(impl));
}

Controller Controller::load_bc(const std::string& run, const std::string& task) {
  auto impl = std::make_unique<Impl>();
  impl->env = task_env(task);
  impl->policy = agent_mean_policy(load_bc_agent(run, impl->env->obs_dim(), impl->env->act_dim(), torch::kCPU));
  return Controller(std::move(impl));
}

int Controller::obs_dim() const { return impl_->env->obs_dim(); }
int Controller::act_dim() const { return impl_->env->act_dim(); }
int Controller::latent_dim() const { return impl_->vae.is_empty() ? 0 : impl_->vae->config().latent_dim; }
double Controller::control_timestep() const { return impl_->env->control_timestep(); }

std::vector<float> Controller::embed(const std::vector<float>& states) const {
  const size_t D = obs_dim();
  if (states.empty() || states.size() % D != 0)
    throw std::invalid_argument("Controller::embed: states has " + std::to_string(states.size()) +
                                " values, not a positive multiple of the observation size " + std::to_string(D));
  if (latent_dim() == 0) return {};
  return to_vector(vae::encode(impl_->vae, tensor_of(states, {1, -1, static_cast<int64_t>(D)})).first);
}

std::vector<float> Controller::act(const std::vector<float>& observation, const std::vector<float>& z) const {
  check_size("the observation", observation.size(), obs_dim());
  check_size("z", z.size(), latent_dim());
  torch::NoGradGuard no_grad;
  return to_vector(impl_->policy(tensor_of(observation, {1, obs_dim()}), tensor_of(z, {1, latent_dim()})));
}

std::vector<float> Controller::observe(const mjModel_* model, const mjData_* data) {
  auto* env = dynamic_cast<MujocoEnv*>(impl_->env.get());
  if (!env) throw std::logic_error("Controller::observe: task '" + impl_->env->id() + "' is not a MuJoCo task");
  env->set_state(model, data);
  return env->observation();
}

}  // namespace vaegail
