#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "cli/task_options.h"
#include "data/record.h"
#include "env/mujoco_env.h"
#include "experts/scripted_gait.h"
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
  int styles = 3;
  bool styles_given = false;
  std::string out;
  std::uint64_t seed = 0;
  int envs = 8;
  int threads = 1;
  std::vector<double> context;
  bool force = false;
};

// The scripted gait's episodes: episode i plays style i mod K, recorded as its context entry
// "style" and its expert id "gait_NAME", so that later stages tell the behaviours apart.
struct GaitPlan {
  std::vector<GaitStyle> styles;
  std::vector<int> style_of_episode;
  BatchPolicy policy;
};

GaitPlan plan_gait(const RolloutOptions& o, const Env& env, RecordRequest& request) {
  const auto* body = dynamic_cast<const MujocoEnv*>(&env);
  if (!body) throw std::invalid_argument("--policy gait: task '" + env.id() + "' is not a MuJoCo body");
  GaitPlan plan;
  plan.styles = gait_styles(body->model(), env.id(), o.styles, o.seed);
  const auto& names = env.context_names();
  const size_t slot = std::find(names.begin(), names.end(), "style") - names.begin();
  if (slot == names.size())  // a built-in task keeps its own context
    throw std::invalid_argument("--policy gait: task '" + env.id() + "' cannot record a style context (an MJCF "
                                "body's generic task can)");
  for (int i = 0; i < o.episodes; ++i) {
    plan.style_of_episode.push_back(i % o.styles);
    request.contexts.push_back(env.context());
    request.contexts.back()[slot] = i % o.styles;
  }
  auto gait = std::make_shared<const ScriptedGait>(body->model(), env.id(), plan.styles);
  plan.policy = scripted_gait_policy(gait, *body, plan.style_of_episode);
  return plan;
}

// Per style: episodes, falls (episodes that ended terminated), mean control steps, and the
// episodes' mean com speed and, when the task names a fall body, its mean height.
void print_style_summary(const GaitPlan& plan, const std::vector<Episode>& episodes, const Env& env) {
  const auto& features = env.feature_names();
  const auto fallen = std::find(features.begin(), features.end(), "fallen");
  const std::string height = fallen != features.end() && fallen != features.begin() ? *(fallen - 1) : "";
  std::printf("\n%-3s %-12s %8s %6s %10s %10s", "", "style", "episodes", "falls", "mean steps", "com_speed");
  if (!height.empty()) std::printf(" %12s", height.c_str());
  std::printf("\n");
  for (size_t k = 0; k < plan.styles.size(); ++k) {
    int count = 0, falls = 0;
    double steps = 0, speed = 0, z = 0;
    for (size_t i = 0; i < episodes.size(); ++i) {
      if (plan.style_of_episode[i] != static_cast<int>(k)) continue;
      const Episode& e = episodes[i];
      ++count;
      falls += !e.terminations.empty() && e.terminations.back();
      steps += e.length();
      speed += e.attributes.at("mean_com_speed");
      if (!height.empty()) z += e.attributes.at("mean_" + height);
    }
    if (count == 0) continue;
    std::printf("%-3zu %-12s %8d %6d %10.1f %10.3f", k, plan.styles[k].name.c_str(), count, falls, steps / count,
                speed / count);
    if (!height.empty()) std::printf(" %12.3f", z / count);
    std::printf("\n");
  }
}

void run_rollout(const RolloutOptions& o) {
  if (std::filesystem::exists(o.out) && !o.force)
    throw std::runtime_error(o.out + ": exists (pass --force to replace it)");
  const bool gait = o.policy == "gait";
  if (o.styles_given && !gait) throw std::invalid_argument("--styles is for --policy gait");
  EnvRequest env_request = o.task.request();
  if (gait) env_request.context_names.push_back("style");
  auto env = make_env(env_request);
  if (!o.context.empty()) env->set_context(o.context);
  RecordRequest request;
  for (int i = 0; i < o.episodes; ++i) request.seeds.push_back(derive_seed(o.seed, i));
  request.expert_id = o.policy;
  request.num_envs = o.envs;
  request.num_threads = o.threads;
  GaitPlan plan;
  if (gait) plan = plan_gait(o, *env, request);
  const BatchPolicy policy = gait ? plan.policy : o.policy == "zero" ? zero_policy(*env) : random_policy(*env, o.seed);
  DemoWriter writer(o.out, header_for(*env));  // fails now, not after the rollout, on a bad path
  Progress progress("rollout", o.episodes, "episodes");
  auto episodes = record_episodes(*env, request, policy, &progress);
  progress.finish();
  for (size_t i = 0; i < episodes.size() && gait; ++i)
    episodes[i].expert_id = "gait_" + plan.styles[plan.style_of_episode[i]].name;
  for (const auto& e : episodes) writer.append(e);
  writer.commit();
  long steps = 0;
  for (const auto& e : episodes) steps += e.length();
  std::printf("wrote %s: %d episodes, %ld steps\n", o.out.c_str(), o.episodes, steps);
  if (gait) print_style_summary(plan, episodes, *env);
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
  roll->add_option("--policy", rollout->policy,
                   "random (uniform in the action bounds), zero, or gait: the scripted gait of src/"
                   "experts/scripted_gait.h (an MJCF body whose actuators are motors on hinge joints; its styles "
                   "from the MJCF's vaegail_gait_style_* entries, else drawn from --seed), each episode's style "
                   "recorded as its context 'style'")
      ->check(CLI::IsMember({"random", "zero", "gait"}))->capture_default_str();
  CLI::Option* styles =
      roll->add_option("--styles", rollout->styles, "--policy gait: K styles, episode i playing style i mod K")
          ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  roll->add_option("--episodes", rollout->episodes, "number of episodes")->check(CLI::Range(1, 1 << 30))->capture_default_str();
  roll->add_option("--out", rollout->out, "output .h5 file")->required();
  roll->add_option("--seed", rollout->seed, "seed of episode resets, random actions and drawn gait styles")
      ->capture_default_str();
  roll->add_option("--envs", rollout->envs, "environments stepped together")->check(CLI::Range(1, 1 << 30))->capture_default_str();
  roll->add_option("--threads", rollout->threads, "threads stepping them")->check(CLI::Range(1, 1 << 30))->capture_default_str();
  roll->add_option("--context", rollout->context, "task context, e.g. the walker's target speed");
  roll->add_flag("--force", rollout->force, "replace an existing output file");
  roll->callback([rollout, styles] {
    rollout->styles_given = styles->count() > 0;
    run_rollout(*rollout);
  });
}

}  // namespace vaegail::cli
