#include "cli/task_options.h"

#include "cli/commands.h"

#include <algorithm>
#include <stdexcept>

namespace vaegail::cli {

EnvRequest TaskOptions::request() const {
  EnvRequest r;
  r.task = task;
  r.episode_length = episode_length;
  r.frame_skip = frame_skip;
  r.terminate_on_fall = !keep_going_after_fall;
  return r;
}

void add_task_options(CLI::App& command, TaskOptions& o) {
  command.add_option("--task", o.task, "built-in task (walker, arm) or the path of an MJCF .xml file")
      ->capture_default_str();
  command.add_option("--episode-length", o.episode_length, "control steps per episode (0: the task's default)")
      ->check(CLI::Range(0, 1 << 30));
  command.add_option("--frame-skip", o.frame_skip, "MJCF files: physics steps per control step")
      ->check(CLI::Range(1, 1 << 30))->capture_default_str();
  command.add_flag("--no-fall-termination", o.keep_going_after_fall,
                   "do not end episodes when the body falls");
}

torch::Device parse_device(const std::string& name) {
  if (name == "cpu") return torch::kCPU;
  if (name == "cuda") {
    if (!torch::cuda::is_available())
      throw std::invalid_argument("--device cuda: this LibTorch build has no CUDA or sees no GPU");
    return torch::kCUDA;
  }
  throw std::invalid_argument("--device must be cpu or cuda, not '" + name + "'");
}

CLI::Option* add_device_option(CLI::App& command, std::string& device, const std::string& description) {
  return command.add_option("--device", device, description)->check(CLI::IsMember({"cpu", "cuda"}))->capture_default_str();
}

CLI::Option* add_refine_options(CLI::App& command, vae::RefineOptions& refine, const std::string& whose) {
  auto* steps = command.add_option("--refine-steps", refine.steps,
                                   "Adam steps moving " + whose + " from the encoder's mean towards the mode of "
                                   "p(z | demonstration) under the decoders (0: the encoder's mean, as the paper)")
                    ->check(CLI::Range(0, 100000))->capture_default_str();
  command.add_option("--refine-lr", refine.learning_rate, "Adam's learning rate for --refine-steps")
      ->check(CLI::PositiveNumber)->capture_default_str();
  return steps;
}

EnvRequest demo_env_request(const DemoSet& demos) {
  EnvRequest request;
  request.task = demos.header.env_id;
  for (const auto& e : demos.episodes) request.episode_length = std::max(request.episode_length, e.length());
  return request;
}

std::unique_ptr<Env> demo_env(const DemoSet& demos, const vae::TrajectoryVae& model) {
  auto env = demo_env(demos);
  if (env->obs_dim() != model->config().state_dim || env->act_dim() != model->config().action_dim)
    throw std::invalid_argument("env '" + demos.header.env_id + "' does not match the VAE's dimensions");
  return env;
}

}  // namespace vaegail::cli
