#include "experts/arm_expert.h"

#include <algorithm>
#include <filesystem>
#include <fmt/format.h>

#include "env/arm.h"
#include "util/atomic_file.h"
#include "util/csv_log.h"
#include "util/json_file.h"
#include "util/rng.h"

namespace vaegail {

namespace fs = std::filesystem;

std::vector<ArmExpertSpec> arm_expert_specs(int count, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<ArmExpertSpec> specs;
  for (int i = 0; i < count; ++i) {
    specs.push_back({fmt::format("reach_{:02}", i), ArmEnv::random_target(rng), derive_seed(seed, i)});
  }
  return specs;
}

// Tuned on four targets (docs/results.md): γ = 0.99 and noise 0.1 rad left actors stuck 20 to
// 50 cm away; a 10-step horizon (the servos settle in ~6) and 0.2 rad reach within ~4 cm.
DdpgOptions ArmExpertOptions::default_ddpg() {
  DdpgOptions d;
  d.actor_hidden = {128, 128};
  d.critic_hidden = {128, 128};
  d.actor_learning_rate = 3e-4;
  d.gamma = 0.9;
  d.warmup_steps = 1000;
  d.exploration_std = 0.2;  // rad on a joint command
  return d;
}

void to_json(nlohmann::json& j, const ArmExpertSpec& s) {
  j = {{"id", s.id}, {"target", s.target}, {"seed", s.seed}};
}

void from_json(const nlohmann::json& j, ArmExpertSpec& s) {
  s.id = j.at("id");
  s.target = j.at("target").get<std::vector<double>>();
  s.seed = j.at("seed");
  if (s.target.size() != 3) throw std::invalid_argument("arm expert " + s.id + ": the target needs x, y, z");
}

void to_json(nlohmann::json& j, const ArmExpertOptions& o) {
  const DdpgOptions& d = o.ddpg;
  j = {{"total_steps", o.total_steps}, {"eval_every", o.eval_every}, {"posture_cost", o.posture_cost},
       {"actor_hidden", d.actor_hidden},
       {"critic_hidden", d.critic_hidden}, {"actor_learning_rate", d.actor_learning_rate},
       {"critic_learning_rate", d.critic_learning_rate}, {"gamma", d.gamma}, {"tau", d.tau},
       {"batch_size", d.batch_size}, {"exploration_std", d.exploration_std}, {"warmup_steps", d.warmup_steps},
       {"pre_activation_penalty", d.pre_activation_penalty}};
}

void from_json(const nlohmann::json& j, ArmExpertOptions& o) {
  const ArmExpertOptions def;
  DdpgOptions& d = o.ddpg;
  o.total_steps = j.value("total_steps", def.total_steps);
  o.eval_every = j.value("eval_every", def.eval_every);
  o.posture_cost = j.value("posture_cost", def.posture_cost);
  d.actor_hidden = j.value("actor_hidden", def.ddpg.actor_hidden);
  d.critic_hidden = j.value("critic_hidden", def.ddpg.critic_hidden);
  d.actor_learning_rate = j.value("actor_learning_rate", def.ddpg.actor_learning_rate);
  d.critic_learning_rate = j.value("critic_learning_rate", def.ddpg.critic_learning_rate);
  d.gamma = j.value("gamma", def.ddpg.gamma);
  d.tau = j.value("tau", def.ddpg.tau);
  d.batch_size = j.value("batch_size", def.ddpg.batch_size);
  d.exploration_std = j.value("exploration_std", def.ddpg.exploration_std);
  d.warmup_steps = j.value("warmup_steps", def.ddpg.warmup_steps);
  d.pre_activation_penalty = j.value("pre_activation_penalty", def.ddpg.pre_activation_penalty);
}

namespace {

// The buffer holds the whole run, so nothing is forgotten and nothing is over-allocated.
std::shared_ptr<Ddpg> make_arm_ddpg(const ArmExpertSpec& spec, const ArmExpertOptions& options, const Env& env,
                                    std::int64_t capacity) {
  DdpgOptions d = options.ddpg;
  d.seed = spec.seed;
  d.buffer_capacity = capacity;
  return std::make_shared<Ddpg>(env.obs_dim(), env.action_spec(), d);
}

// One noise-free episode (the start and the actor are deterministic): return, the final
// grip-to-target distance and the grip path's ratio of length to displacement.
ArmExpertResult evaluate_actor(Ddpg& ddpg, const ArmEnv& prototype) {
  torch::NoGradGuard no_grad;
  const auto copy = prototype.clone();
  auto& env = dynamic_cast<ArmEnv&>(*copy);
  env.reset(0);
  ArmExpertResult r;
  const auto start = env.grip_position();
  auto previous = start;
  double path_length = 0;
  for (bool done = false; !done;) {
    const auto action = ddpg.act(torch::tensor(env.observation()).unsqueeze(0)).squeeze(0).contiguous();
    const StepOutcome out = env.step(action.data_ptr<float>());
    r.best_return += out.reward;
    done = out.done();
    const auto now = env.grip_position();
    path_length += point_distance(previous, now);
    previous = now;
  }
  r.final_distance = env.target_distance();
  r.path_ratio = path_length / std::max(point_distance(start, previous), 1e-6);
  return r;
}

ArmExpertResult read_result(const std::string& run_dir) {
  const auto j = read_json_file(run_dir + "/state.json");
  // Runs published before the path ratio was recorded read as 0.
  return {j.at("best_return").get<double>(), j.at("final_distance").get<double>(), j.value("path_ratio", 0.0)};
}

std::unique_ptr<ArmEnv> arm_for(const ArmExpertSpec& spec, const ArmExpertOptions& options) {
  ArmOptions arm;
  arm.posture_cost = options.posture_cost;
  auto env = std::make_unique<ArmEnv>(arm);
  env->set_context(spec.target);
  return env;
}

}  // namespace

bool arm_expert_done(const std::string& run_dir) { return fs::exists(run_dir + "/state.json"); }

ArmExpertResult train_arm_expert(const ArmExpertSpec& spec, const ArmExpertOptions& options,
                                 const std::string& run_dir, const std::function<void(std::int64_t)>& progress) {
  if (arm_expert_done(run_dir)) return read_result(run_dir);
  if (options.eval_every < 1 || options.total_steps < options.eval_every)
    throw std::invalid_argument("arm expert: total_steps must be at least eval_every, which must be positive");
  fs::create_directories(run_dir);
  write_file_atomically(run_dir + "/spec.json", nlohmann::json(spec).dump(2));
  write_file_atomically(run_dir + "/options.json", nlohmann::json(options).dump(2));
  fs::remove(run_dir + "/metrics.csv");  // an interrupted run starts over

  const auto env = arm_for(spec, options);
  auto ddpg = make_arm_ddpg(spec, options, *env, options.total_steps);
  CsvLog log(run_dir + "/metrics.csv", {"steps", "critic_loss", "actor_objective", "return", "final_distance", "path_ratio"});
  ArmExpertResult best{-1.0, 0.0};
  while (ddpg->steps_trained() < options.total_steps) {
    const DdpgStats stats =
        ddpg->train(*env, std::min<std::int64_t>(options.eval_every, options.total_steps - ddpg->steps_trained()));
    const ArmExpertResult now = evaluate_actor(*ddpg, *env);
    log.write({{"steps", ddpg->steps_trained()},
               {"critic_loss", stats.critic_loss},
               {"actor_objective", stats.actor_objective},
               {"return", now.best_return},
               {"final_distance", now.final_distance},
               {"path_ratio", now.path_ratio}});
    if (now.best_return >= best.best_return) {
      best = now;
      ddpg->save_actor(run_dir + "/actor.pt");
    }
    if (progress) progress(ddpg->steps_trained());
  }
  write_file_atomically(run_dir + "/state.json",
                        nlohmann::json{{"done", true}, {"best_return", best.best_return},
                                       {"final_distance", best.final_distance},
                                       {"path_ratio", best.path_ratio}}.dump(2));
  return best;
}

LoadedArmExpert load_arm_expert(const std::string& run_dir) {
  for (const char* file : {"spec.json", "options.json", "actor.pt", "state.json"})
    if (!fs::exists(run_dir + "/" + file))
      throw std::runtime_error(run_dir + ": not a finished arm expert run (missing " + file + ")");
  LoadedArmExpert e;
  e.spec = read_json_file(run_dir + "/spec.json").get<ArmExpertSpec>();
  e.options = read_json_file(run_dir + "/options.json").get<ArmExpertOptions>();
  e.result = read_result(run_dir);
  e.ddpg = make_arm_ddpg(e.spec, e.options, *arm_for(e.spec, e.options), 1);
  e.ddpg->load_actor(run_dir + "/actor.pt");
  return e;
}

namespace {
// The expert's actor: its joint commands, clipped to the action box.
BatchPolicy arm_expert_policy(std::shared_ptr<Ddpg> ddpg, const BoxSpec& action_spec) {
  return [ddpg, action_spec](int n, const float* observations, const int*, const int*, float* actions) {
    torch::NoGradGuard no_grad;
    const int obs_dim = ddpg->actor().in_dim(), act_dim = action_spec.dim();
    const auto obs = torch::from_blob(const_cast<float*>(observations), {n, obs_dim});
    const auto mean = ddpg->act(obs).contiguous();
    const float* m = mean.data_ptr<float>();
    for (int b = 0; b < n; ++b)
      for (int a = 0; a < act_dim; ++a)
        actions[b * act_dim + a] = static_cast<float>(
            std::clamp(static_cast<double>(m[b * act_dim + a]), action_spec.low[a], action_spec.high[a]));
  };
}
}  // namespace

void collect_arm_demos(const std::vector<std::string>& expert_dirs, const std::string& out_path,
                       const ArmCollectOptions& o, Progress* progress) {
  const ArmEnv prototype;
  DemoWriter writer(out_path, header_for(prototype));
  for (size_t x = 0; x < expert_dirs.size(); ++x) {
    const LoadedArmExpert expert = load_arm_expert(expert_dirs[x]);
    RecordRequest request;
    for (int k = 0; k < o.episodes_per_expert; ++k) {
      request.seeds.push_back(derive_seed(derive_seed(o.seed, x), k));
      request.contexts.push_back(expert.spec.target);
    }
    request.expert_id = expert.spec.id;
    request.num_envs = o.num_envs;
    request.execution_noise_std = o.noise_std;
    request.execution_noise_seed = derive_seed(o.seed, 1000 + x);
    const bool held_out = std::count(o.held_out.begin(), o.held_out.end(), expert.spec.id) > 0;
    BatchPolicy policy = arm_expert_policy(expert.ddpg, prototype.action_spec());
    if (o.offset_std > 0)
      policy = with_episode_offset(std::move(policy), prototype.action_spec(), o.offset_std, derive_seed(o.seed, 2000 + x));
    auto episodes = record_episodes(prototype, request, policy, progress);
    for (auto& e : episodes) {
      e.attributes["held_out"] = held_out ? 1.0 : 0.0;
      const int n_features = static_cast<int>(prototype.feature_names().size());
      e.attributes["final_distance"] = e.features[e.length() * n_features + n_features - 1];
      writer.append(e);
    }
  }
  writer.commit();
}

}  // namespace vaegail
