#include "experts/expert_trainer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "env/registry.h"
#include "env/vec_env.h"
#include "env/walker.h"
#include "rl/distributed.h"
#include "rl/rollout.h"
#include "rl/update_batch.h"
#include "util/atomic_file.h"
#include "util/checkpoint_file.h"
#include "util/csv_log.h"
#include "util/json_file.h"
#include "util/malloc_tuning.h"
#include "util/rng.h"
#include "util/world.h"

namespace vaegail {

namespace fs = std::filesystem;

std::unique_ptr<Env> make_expert_env(const ExpertSpec& spec, double posture_cost) {
  if (spec.targets.empty()) throw std::invalid_argument(spec.id + ": no target");
  std::unique_ptr<Env> env;
  if (spec.task == "walker") {
    WalkerOptions walker;
    walker.posture_cost = posture_cost;
    env = std::make_unique<WalkerEnv>(walker);
  } else if (posture_cost != 0.0) {
    throw std::invalid_argument(spec.id + ": posture_cost is the walker's, not " + spec.task + "'s");
  } else {
    EnvRequest request;
    request.task = spec.task;
    env = make_env(request);
  }
  env->set_context({spec.targets[0]});
  return env;
}

std::shared_ptr<Agent> make_expert_agent(const ExpertSpec& spec, const ExpertTrainOptions& options,
                                         int obs_dim, int act_dim) {
  torch::manual_seed(spec.seed);
  AgentOptions a;
  a.obs_dim = obs_dim;
  a.condition_dim = spec.condition_dim();
  a.act_dim = act_dim;
  a.policy_hidden = options.hidden;
  a.critic_hidden = options.hidden;
  a.init_log_std = spec.init_log_std;
  auto agent = Agent::make_gaussian(a);
  agent->to(torch::Device(options.device));
  return agent;
}

namespace {

struct RunState {
  int iteration = 0;
  std::int64_t steps = 0;
  bool done = false;
  double seconds = 0;  // training wall-clock up to the checkpoint, summed over resumed calls
};

nlohmann::json state_json(const RunState& s) {
  return {{"iteration", s.iteration}, {"steps", s.steps}, {"done", s.done}, {"seconds", s.seconds}};
}

RunState state_of(const nlohmann::json& j) {
  RunState s;
  s.iteration = j.at("iteration");
  s.steps = j.at("steps");
  s.done = j.at("done");
  s.seconds = j.value("seconds", 0.0);
  return s;
}

// state.json, for readers that do not load the agent (expert_done, expert_steps).
RunState read_state(const std::string& run_dir) {
  const std::string path = run_dir + "/state.json";
  return fs::exists(path) ? state_of(read_json_file(path)) : RunState{};
}

// The state agent.pt was saved in. The checkpoint carries it: a kill between writing agent.pt
// and state.json would otherwise resume the new weights at the old iteration count. An expert
// trained before has none there, and goes by state.json.
RunState checkpoint_state(const std::string& run_dir) {
  const std::string path = run_dir + "/agent.pt";
  if (!fs::exists(path)) return read_state(run_dir);
  std::string state;
  read_checkpoint(path, [&](const std::string& file) {
    torch::serialize::InputArchive archive;
    archive.load_from(file);
    c10::IValue value;
    if (archive.try_read("state", value)) state = value.toStringRef();
  });
  return state.empty() ? read_state(run_dir) : state_of(nlohmann::json::parse(state));
}

void save(const Agent& agent, const RunState& s, const std::string& run_dir) {
  torch::serialize::OutputArchive archive;
  agent.save(archive);
  archive.write("state", c10::IValue(state_json(s).dump()));
  write_checkpoint(run_dir + "/agent.pt", [&](std::ostream& out) { archive.save_to(out); });
  write_file_atomically(run_dir + "/state.json", state_json(s).dump(2));
}

// The walker's mean |forward speed - target| over the rollout's steps: a cheap training-time
// signal (the torso's speed stands in for the centre of mass's); `vaegail experts eval`
// measures properly. NaN for tasks whose context is no speed (the humanoid's style).
double speed_error(const Rollout& r, const ExpertSpec& spec, const Env& env) {
  const auto& names = env.observation_spec().names;
  const auto speed_at = std::find(names.begin(), names.end(), "rootx_vel");
  if (spec.task != "walker" || speed_at == names.end()) return std::nan("");
  torch::Tensor speed = r.observations.select(2, static_cast<int64_t>(speed_at - names.begin()));
  torch::Tensor target = spec.conditioned() ? r.conditions.select(2, 0)
                                            : torch::full_like(speed, spec.targets[0]);
  return (speed - target).abs().mean().item<double>();
}

}  // namespace

bool expert_done(const std::string& run_dir) { return read_state(run_dir).done; }

std::int64_t expert_steps(const std::string& run_dir) { return read_state(run_dir).steps; }

void train_expert(const ExpertSpec& spec, const ExpertTrainOptions& options, const std::string& run_dir,
                  const std::function<void(std::int64_t)>& progress) {
  auto prototype = make_expert_env(spec, options.posture_cost);  // checks the spec before touching run_dir
  retain_freed_memory();  // the rollout buffers and minibatch activations come back every iteration
  // Under mpirun every rank steps its share of the environments (rl/distributed.h); rank 0
  // alone writes the run directory, the others read it once rank 0 has set it up.
  const World& world = World::get();
  const EnvSlice slice = EnvSlice::of_world(options.num_envs);
  const std::string spec_path = run_dir + "/spec.json";
  if (fs::exists(spec_path)) {
    const ExpertSpec existing = read_json_file(spec_path).get<ExpertSpec>();
    if (existing.id != spec.id)
      throw std::runtime_error(run_dir + " holds expert " + existing.id + ", not " + spec.id);
  }
  world.barrier();  // every rank has read what was there before rank 0 writes
  if (world.is_root()) {
    fs::create_directories(run_dir);
    if (!fs::exists(spec_path)) write_file_atomically(spec_path, nlohmann::json(spec).dump(2));
    write_file_atomically(run_dir + "/options.json", nlohmann::json(options).dump(2));
  }

  auto agent = make_expert_agent(spec, options, prototype->obs_dim(), prototype->act_dim());
  RunState state = checkpoint_state(run_dir);
  if (state.iteration > 0) agent->load_checkpoint(run_dir + "/agent.pt");
  const std::string metrics_path = run_dir + "/metrics.csv";
  if (world.is_root()) {
    // What a kill after the checkpoint left: rows of iterations the resumed run redoes, a stale
    // state.json.
    truncate_metrics(metrics_path, state.iteration);
    if (read_state(run_dir).iteration != state.iteration)
      write_file_atomically(run_dir + "/state.json", state_json(state).dump(2));
  }
  if (state.steps >= options.total_steps) return;

  VecEnv envs(*prototype, slice.count, options.env_threads);
  // Streams restart from the iteration count, so a resumed run is reproducible too; each of the
  // run's environments draws its targets from its own, whichever rank steps it.
  std::vector<Rng> target_rngs;
  for (int i = 0; i < slice.count; ++i) target_rngs.emplace_back(derive_seed(derive_seed(spec.seed, 1000 + state.iteration), slice.first + i));
  EpisodeStartFn choose_target = [&](int env_index, Env& env) -> std::vector<float> {
    const double target = spec.targets[target_rngs[env_index].next() % spec.targets.size()];
    env.set_context({target});
    return spec.condition_for(target);
  };
  RolloutCollector collector(envs, agent, derive_seed(spec.seed, state.iteration), choose_target,
                             std::make_shared<EnvReward>(), slice);
  PpoOptions ppo_options;
  ppo_options.learning_rate = options.learning_rate;
  ppo_options.epochs = options.epochs;
  ppo_options.minibatches = options.minibatches;
  ppo_options.target_kl = options.target_kl;
  ppo_options.seed = derive_seed(spec.seed, 2000 + state.iteration);
  Ppo ppo(agent->policy_ptr(), agent->critic_ptr(), ppo_options);
  std::unique_ptr<CsvLog> log;
  if (world.is_root())
    log = std::make_unique<CsvLog>(metrics_path,
                                   std::vector<std::string>{"iteration", "steps", "episodes", "mean_return",
                                                            "mean_length", "fall_rate", "speed_error", "approx_kl",
                                                            "entropy", "value_loss", "seconds"});
  const auto start = std::chrono::steady_clock::now();
  const double seconds_before = state.seconds;

  while (state.steps < options.total_steps) {
    const Rollout rollout = collector.collect(options.steps_per_env);
    const PpoStats stats = ppo.update(make_update_batch(rollout, options.gamma, options.lambda, slice));
    state.steps += static_cast<std::int64_t>(options.steps_per_env) * options.num_envs;
    ++state.iteration;
    state.seconds = seconds_before + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // The run's episodes: this rank's sums, added over the ranks.
    std::vector<double> sums = {static_cast<double>(rollout.episodes.size()), 0, 0, 0};
    for (const auto& e : rollout.episodes) {
      sums[1] += e.env_return;
      sums[2] += e.length;
      sums[3] += e.terminated;
    }
    world.sum(sums.data(), static_cast<std::int64_t>(sums.size()));
    const double speed = all_sum(speed_error(rollout, spec, *prototype)) / world.size();
    const double n = std::max(sums[0], 1.0);
    state.done = state.steps >= options.total_steps;
    if (world.is_root()) {
      log->write({{"iteration", state.iteration},
                  {"steps", state.steps},
                  {"episodes", sums[0]},
                  {"mean_return", sums[1] / n},
                  {"mean_length", sums[2] / n},
                  {"fall_rate", sums[3] / n},
                  {"speed_error", speed},
                  {"approx_kl", stats.approx_kl},
                  {"entropy", stats.entropy},
                  {"value_loss", stats.value_loss},
                  {"seconds", state.seconds}});
      if (state.done || state.iteration % options.checkpoint_every == 0) save(*agent, state, run_dir);
    }
    if (progress) progress(state.steps);
  }
}

LoadedExpert load_expert(const std::string& run_dir) {
  for (const char* file : {"spec.json", "options.json", "agent.pt"})
    if (!fs::exists(run_dir + "/" + file))
      throw std::runtime_error(run_dir + ": not an expert run (missing " + file + ")");
  LoadedExpert e;
  e.spec = read_json_file(run_dir + "/spec.json").get<ExpertSpec>();
  e.options = read_json_file(run_dir + "/options.json").get<ExpertTrainOptions>();
  const auto prototype = make_expert_env(e.spec);
  e.agent = make_expert_agent(e.spec, e.options, prototype->obs_dim(), prototype->act_dim());
  e.agent->load_checkpoint(run_dir + "/agent.pt");
  e.agent->normalizer().set_frozen(true);
  e.agent->eval();
  return e;
}

}  // namespace vaegail
