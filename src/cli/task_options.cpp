#include "cli/task_options.h"

#include "cli/app.h"
#include "cli/commands.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "util/atomic_file.h"
#include "util/sha256.h"

namespace vaegail::cli {

namespace {
bool ends_with_xml(const std::string& s) { return s.size() >= 4 && s.compare(s.size() - 4, 4, ".xml") == 0; }
}  // namespace

void ensure_published_walker_demos(const std::string& demos) {
  if (demos != kPublishedWalkerDemos || std::filesystem::exists(demos)) return;
  std::printf("%s is not in this checkout: collecting it from the committed experts (under a minute)\n",
              demos.c_str());
  // The same command line as scripts/reproduce/walker.sh's `demos` stage.
  run_command_line("demos collect --experts-dir experts/walker --passing experts/walker/eval.json --out " + demos +
                   " --episodes-per-expert 20 --force"
                   " --held-out speed-1_logstd-1_seed3 speed0_logstd-1_seed3 speed1_logstd-1_seed3");
}

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
  command.add_option("--frame-skip", o.frame_skip,
                     "MJCF files: physics steps per control step (0: the MJCF's vaegail_frame_skip, else 1)")
      ->check(CLI::Range(0, 1 << 30))->capture_default_str();
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
  const DemoHeader& h = demos.header;
  EnvRequest request;
  request.task = h.env_id;
  for (const auto& e : demos.episodes) request.episode_length = std::max(request.episode_length, e.length());
  const auto& builtin = builtin_tasks();
  const bool by_name = std::find(builtin.begin(), builtin.end(), h.env_id) != builtin.end();
  if (h.body_mjcf.empty() && !by_name && !ends_with_xml(h.env_id))
    throw std::invalid_argument(demos.path + ": recorded on '" + h.env_id +
                                "', which is neither built in nor stored in the file (give it a body: "
                                "vaegail data import FILE --task BODY.xml --out NEW.h5)");
  request.mjcf_text = h.body_mjcf;
  request.context_names = h.context_names;
  request.control_timestep = h.control_timestep;
  return request;
}

void check_demo_task(const DemoSet& demos, const std::string& task) {
  const DemoHeader& h = demos.header;
  if (task.empty() || (h.body_mjcf.empty() && task == h.env_id)) return;
  if (h.body_mjcf.empty())
    throw std::invalid_argument(demos.path + ": recorded on task '" + h.env_id + "', not on --task " + task);
  const std::string stored = sha256_hex(h.body_mjcf);
  const std::string given = ends_with_xml(task) ? sha256_hex(read_file(task)) : "";
  if (given != stored)
    throw std::invalid_argument(demos.path + ": recorded on body " + h.env_id + " (sha256 " + stored.substr(0, 12) +
                                "), not on --task " + task +
                                (given.empty() ? " (a built-in task)" : " (sha256 " + given.substr(0, 12) + ")"));
}

void add_demo_task_option(CLI::App& command, std::string& task) {
  command.add_option("--task", task,
                     "check that the demonstrations were recorded on this task or MJCF file (the file's own body "
                     "is used either way)");
}

std::unique_ptr<Env> demo_env(const DemoSet& demos, const vae::TrajectoryVae& model) {
  auto env = demo_env(demos);
  if (env->obs_dim() != model->config().state_dim || env->act_dim() != model->config().action_dim)
    throw std::invalid_argument("env '" + demos.header.env_id + "' does not match the VAE's dimensions");
  return env;
}

}  // namespace vaegail::cli
