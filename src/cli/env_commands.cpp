#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "cli/task_options.h"
#include "data/record.h"
#include "util/progress.h"
#include "util/rng.h"

namespace vaegail::cli {

namespace {

void print_env_info(const Env& env) {
  std::printf("task              %s\n", env.id().c_str());
  std::printf("control timestep  %g s\n", env.control_timestep());
  std::printf("episode length    %d steps (%g s)\n", env.episode_length(), env.episode_length() * env.control_timestep());
  std::printf("\nobservation (%d)\n", env.obs_dim());
  for (int i = 0; i < env.obs_dim(); ++i) std::printf("  %3d  %s\n", i, env.observation_spec().names[i].c_str());
  std::printf("\naction (%d)\n", env.act_dim());
  for (int i = 0; i < env.act_dim(); ++i)
    std::printf("  %3d  %-20s [%g, %g]\n", i, env.action_spec().names[i].c_str(), env.action_spec().low[i],
                env.action_spec().high[i]);
  std::printf("\nfeatures          ");
  for (const auto& f : env.feature_names()) std::printf("%s ", f.c_str());
  std::printf("\ncontext           ");
  for (size_t i = 0; i < env.context_names().size(); ++i)
    std::printf("%s (default %g) ", env.context_names()[i].c_str(), env.context()[i]);
  std::printf("\n");
}

struct RolloutOptions {
  TaskOptions task;
  std::string policy = "random";
  int episodes = 10;
  std::string out;
  std::uint64_t seed = 0;
  int envs = 8;
  int threads = 1;
  std::vector<double> context;
  bool force = false;
};

void run_rollout(const RolloutOptions& o) {
  if (std::filesystem::exists(o.out) && !o.force)
    throw std::runtime_error(o.out + ": exists (pass --force to replace it)");
  auto env = o.task.make();
  if (!o.context.empty()) env->set_context(o.context);
  RecordRequest request;
  for (int i = 0; i < o.episodes; ++i) request.seeds.push_back(derive_seed(o.seed, i));
  request.expert_id = o.policy;
  request.num_envs = o.envs;
  request.num_threads = o.threads;
  const BatchPolicy policy = o.policy == "zero" ? zero_policy(*env) : random_policy(*env, o.seed);
  DemoWriter writer(o.out, header_for(*env));  // fails now, not after the rollout, on a bad path
  Progress progress("rollout", o.episodes, "episodes");
  const auto episodes = record_episodes(*env, request, policy, &progress);
  progress.finish();
  for (const auto& e : episodes) writer.append(e);
  writer.commit();
  long steps = 0;
  for (const auto& e : episodes) steps += e.length();
  std::printf("wrote %s: %d episodes, %ld steps\n", o.out.c_str(), o.episodes, steps);
}

}  // namespace

void add_env_commands(CLI::App& app) {
  CLI::App* env = app.add_subcommand("env", "inspect and roll out environments");
  env->require_subcommand(1);

  auto info = std::make_shared<TaskOptions>();
  CLI::App* info_cmd = env->add_subcommand("info", "print the observation, action, feature and context layout");
  add_task_options(*info_cmd, *info);
  info_cmd->callback([info] { print_env_info(*info->make()); });

  auto rollout = std::make_shared<RolloutOptions>();
  CLI::App* roll = env->add_subcommand("rollout", "roll out a fixed policy and record episodes to HDF5");
  add_task_options(*roll, rollout->task);
  roll->add_option("--policy", rollout->policy, "random (uniform in the action bounds) or zero")
      ->check(CLI::IsMember({"random", "zero"}))->capture_default_str();
  roll->add_option("--episodes", rollout->episodes, "number of episodes")->check(CLI::Range(1, 1 << 30))->capture_default_str();
  roll->add_option("--out", rollout->out, "output .h5 file")->required();
  roll->add_option("--seed", rollout->seed, "seed of episode resets and random actions")->capture_default_str();
  roll->add_option("--envs", rollout->envs, "environments stepped together")->check(CLI::Range(1, 1 << 30))->capture_default_str();
  roll->add_option("--threads", rollout->threads, "threads stepping them")->check(CLI::Range(1, 1 << 30))->capture_default_str();
  roll->add_option("--context", rollout->context, "task context, e.g. the walker's target speed");
  roll->add_flag("--force", rollout->force, "replace an existing output file");
  roll->callback([rollout] { run_rollout(*rollout); });
}

}  // namespace vaegail::cli
