#include "gail/diverse_gail.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "gail/run_dir.h"
#include "rl/distributed.h"
#include "rl/rollout.h"
#include "rl/trpo.h"
#include "rl/update_batch.h"
#include "util/checkpoint_file.h"
#include "util/csv_log.h"
#include "util/malloc_tuning.h"
#include "util/rng.h"
#include "util/world.h"
#include "vae/demo_dataset.h"

namespace vaegail {

namespace fs = std::filesystem;

namespace {

// Random streams of one iteration, each derived from (seed, iteration, stream).
// Numbered after the agent's initial weights (gail_agent.h's kGailInitStream).
enum Stream : std::uint64_t { kDemoDraws = kGailInitStream + 1, kCollect, kTrpo, kDemoSteps, kDiscriminatorBatches };

std::uint64_t stream_seed(std::uint64_t seed, int iteration, Stream stream) {
  return derive_seed(derive_seed(seed, static_cast<std::uint64_t>(iteration) + 1), stream);
}

// Options a resumed run may change: they do not alter what an iteration computes.
const std::vector<std::string> kResumableKeys = {"iterations", "minutes", "device", "env_threads"};

// Which training demonstration each step [T, N] of the rollout imitated: environment i's
// episodes took started[i][0], [1], … in turn, the next one after each done step.
torch::Tensor step_demonstrations(const std::vector<std::vector<int>>& started, const Rollout& rollout) {
  const auto done = ((rollout.terminated + rollout.truncated) > 0).to(torch::kCPU).contiguous();
  const int64_t T = done.size(0), N = done.size(1);
  auto out = torch::empty({T, N}, torch::kLong);
  const auto d = done.accessor<bool, 2>();
  auto o = out.accessor<int64_t, 2>();
  for (int64_t i = 0; i < N; ++i) {
    size_t episode = 0;
    for (int64_t t = 0; t < T; ++t) {
      o[t][i] = started[i].at(episode);
      if (d[t][i]) ++episode;
    }
  }
  return out;
}

// A metrics.csv row: the trainer's metrics and the task's columns, NaN where the task gives none.
Metrics row(const GailMetrics& m) {
  Metrics r = {{"iteration", m.iteration},
               {"steps", m.steps},
               {"episodes", m.episodes},
               {"disc_demo_accuracy", m.demo_accuracy},
               {"disc_policy_accuracy", m.policy_accuracy},
               {"disc_loss", m.discriminator_loss},
               {"gail_reward", m.gail_reward},
               {"env_return", m.env_return},
               {"episode_length", m.episode_length},
               {"fall_rate", m.fall_rate},
               {"kl", m.kl},
               {"entropy", m.entropy},
               {"value_loss", m.value_loss},
               {"seconds", m.seconds}};
  for (const auto& column : gail_task_metric_columns()) r[column] = std::numeric_limits<double>::quiet_NaN();
  for (const auto& [column, value] : m.task) r[column] = value;
  return r;
}

DiscriminatorOptions discriminator_options(const GailOptions& o, const Env& env, int latent_dim) {
  DiscriminatorOptions d;
  d.obs_dim = env.obs_dim();
  d.act_dim = env.act_dim();
  d.latent_dim = latent_dim;
  d.state_indices = o.discriminator_state_indices;
  d.action_low = env.action_spec().low;
  d.action_high = env.action_spec().high;
  d.hidden = o.discriminator_hidden;
  return d;
}

}  // namespace

// In the order existing files have them: the task's columns after fall_rate.
const std::vector<std::string> kGailMetricColumns = [] {
  std::vector<std::string> columns = {"iteration", "steps", "episodes", "disc_demo_accuracy", "disc_policy_accuracy",
                                      "disc_loss", "gail_reward", "env_return", "episode_length", "fall_rate"};
  const auto& task = gail_task_metric_columns();
  columns.insert(columns.end(), task.begin(), task.end());
  columns.insert(columns.end(), {"kl", "entropy", "value_loss", "seconds"});
  return columns;
}();

GailOptions gail_preset(const std::string& name, const Env& env) {
  GailOptions o;
  if (name == "humanoid") {
    o.iterations = 100000;
    o.policy_hidden = {300, 200, 100};
    o.critic_hidden = {300, 200, 100};
    o.discriminator_hidden = {300, 200};
    o.init_log_std = std::log(0.1);
  } else if (name != "walker") {
    throw std::invalid_argument("GAIL: unknown preset '" + name + "' (walker, humanoid)");
  }
  o.discriminator_state_indices = env.discriminator_observation();
  return o;
}

std::string default_gail_preset(const Env& env) { return env.id() == "humanoid" ? "humanoid" : "walker"; }

GailPhaseSeconds& GailPhaseSeconds::operator+=(const GailPhaseSeconds& o) {
  rollout += o.rollout;
  policy_update += o.policy_update;
  discriminator += o.discriminator;
  bookkeeping += o.bookkeeping;
  return *this;
}

GailTrainer::GailTrainer(const DemoSet& demos, vae::TrajectoryVae vae, const Env& prototype, GailOptions options,
                         std::string run_dir)
    : options_(std::move(options)), run_dir_(std::move(run_dir)) {
  retain_freed_memory();  // a rollout's [T, N, ...] buffers and the update's activations, every iteration
  const bool diverse = options_.mode == GailMode::Diverse;
  if (demos.header.obs_dim() != prototype.obs_dim() || demos.header.act_dim() != prototype.act_dim())
    throw std::invalid_argument(demos.path + ": observations/actions have " +
                                std::to_string(demos.header.obs_dim()) + "/" + std::to_string(demos.header.act_dim()) +
                                " components, environment '" + prototype.id() + "' " +
                                std::to_string(prototype.obs_dim()) + "/" + std::to_string(prototype.act_dim()));
  if (diverse) {
    if (vae.is_empty()) throw std::invalid_argument("diverse GAIL needs a VAE");
    const auto& c = vae->config();
    if (c.state_dim != prototype.obs_dim() || c.action_dim != prototype.act_dim())
      throw std::invalid_argument(demos.path + ": observations/actions have " + std::to_string(prototype.obs_dim()) +
                                  "/" + std::to_string(prototype.act_dim()) + " components, the VAE " +
                                  std::to_string(c.state_dim) + "/" + std::to_string(c.action_dim));
    vae->eval();
  }
  if (options_.num_envs < 1 || options_.iterations < 0 || options_.discriminator_steps < 0 ||
      options_.discriminator_minibatches < 1)
    throw std::invalid_argument(
        "GAIL: num_envs and discriminator_minibatches must be positive, iterations and discriminator_steps not negative");

  // Under mpirun every rank trains its share of the environments; rank 0 alone writes.
  const World& world = World::get();
  slice_ = EnvSlice::of_world(options_.num_envs);
  lock_ = lock_run_directory(run_dir_);  // rank 0's: the ranks are one writer
  if (world.is_root()) {
    fs::create_directories(run_dir_ + "/checkpoints");
    check_or_write_config(run_dir_ + "/config.json", options_, kResumableKeys);
  }
  world.barrier();

  demos_ = make_gail_demos(demos, vae::split_demos(demos, options_.seed).train, diverse ? &vae : nullptr);
  envs_ = std::make_unique<VecEnv>(prototype, slice_.count, options_.env_threads);
  steps_per_env_ = options_.steps_per_env > 0 ? options_.steps_per_env : prototype.episode_length();
  task_metrics_ = std::make_unique<GailTaskMetrics>(prototype.observation_spec().names);

  agent_ = make_gail_agent(options_, prototype.obs_dim(), prototype.act_dim(), demos_.observations,
                           diverse ? vae : vae::TrajectoryVae(nullptr));
  discriminator_ = std::make_shared<Discriminator>(
      discriminator_options(options_, prototype, diverse ? demos_.latent_dim() : 0));
  discriminator_->fit_normalization(demos_.observations, demos_.actions);
  discriminator_->to(agent_->device());
  discriminator_trainer_ = std::make_unique<DiscriminatorTrainer>(discriminator_, options_.discriminator_learning_rate);
  reward_ = std::make_shared<GailReward>(discriminator_, options_.reward_clip);
  TrpoOptions trpo_options;
  trpo_options.max_kl = options_.max_kl;
  trpo_options.critic_learning_rate = options_.critic_learning_rate;
  trpo_ = std::make_unique<Trpo>(agent_->policy_ptr(), agent_->critic_ptr(), trpo_options);
  if (fs::exists(checkpoint_path())) load_checkpoint();
  if (world.is_root()) {
    truncate_metrics(metrics_path(), iteration_);
    log_ = std::make_unique<CsvLog>(metrics_path(), kGailMetricColumns);
  }
}

void GailTrainer::save_checkpoint() const {
  torch::serialize::OutputArchive root, agent, discriminator, optimizer, critic_optimizer;
  agent_->save(agent);
  discriminator_->save(discriminator);
  discriminator_trainer_->optimizer().save(optimizer);
  trpo_->critic_optimizer().save(critic_optimizer);
  root.write("agent", agent);
  root.write("discriminator", discriminator);
  root.write("discriminator_optimizer", optimizer);
  root.write("critic_optimizer", critic_optimizer);
  root.write("iteration", torch::tensor(static_cast<int64_t>(iteration_)));
  root.write("seconds", torch::tensor(seconds_before_, torch::kFloat64));
  write_checkpoint(checkpoint_path(), [&](std::ostream& out) { root.save_to(out); });
}

void GailTrainer::load_checkpoint() {
  torch::serialize::InputArchive root, agent, discriminator, optimizer, critic_optimizer;
  root.load_from(checkpoint_path(), agent_->device());
  root.read("agent", agent);
  root.read("discriminator", discriminator);
  root.read("discriminator_optimizer", optimizer);
  agent_->load(agent);
  discriminator_->load(discriminator);
  discriminator_trainer_->optimizer().load(optimizer);
  if (root.try_read("critic_optimizer", critic_optimizer)) trpo_->critic_optimizer().load(critic_optimizer);
  torch::Tensor iteration, seconds;
  root.read("iteration", iteration);
  root.read("seconds", seconds);
  iteration_ = static_cast<int>(iteration.item<int64_t>());
  seconds_before_ = seconds.item<double>();
}

GailMetrics GailTrainer::iterate() {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto lap_start = start;
  const auto lap = [&lap_start] {
    const auto now = Clock::now();
    const double s = std::chrono::duration<double>(now - lap_start).count();
    lap_start = now;
    return s;
  };
  const bool conditional = options_.mode == GailMode::Diverse;
  // Each of the run's environments draws its demonstrations and z from a stream of its own,
  // so the draws do not depend on which rank steps it.
  std::vector<Rng> demo_rngs;
  for (int i = 0; i < envs_->size(); ++i)
    demo_rngs.emplace_back(derive_seed(stream_seed(options_.seed, iteration_, kDemoDraws), slice_.first + i));
  std::vector<std::vector<int>> started(envs_->size());
  EpisodeStartFn start_episode = [&](int env_index, Env& env) {
    Rng& rng = demo_rngs[env_index];
    const int m = static_cast<int>(rng.next() % static_cast<std::uint64_t>(demos_.size()));
    started[env_index].push_back(m);
    if (!demos_.contexts[m].empty()) env.set_context(demos_.contexts[m]);
    return conditional ? demos_.sample_latent(m, rng) : std::vector<float>{};
  };
  RolloutCollector collector(*envs_, agent_, stream_seed(options_.seed, iteration_, kCollect), start_episode,
                             reward_, slice_);
  const Rollout rollout = collector.collect(steps_per_env_);
  last_phases_.rollout = lap();

  trpo_->reseed(stream_seed(options_.seed, iteration_, kTrpo));
  const UpdateBatch batch = make_update_batch(rollout, options_.gamma, options_.lambda, slice_);
  const TrpoStats trpo_stats = trpo_->update(batch);
  last_phases_.policy_update = lap();

  // Each policy step against a step of the demonstration its episode imitated, same z.
  const DiscriminatorData policy{flatten_steps(rollout.observations), flatten_steps(rollout.actions),
                                 flatten_steps(rollout.conditions)};
  const auto demo_of_step = step_demonstrations(started, rollout);
  auto generator = at::detail::createCPUGenerator(stream_seed(options_.seed, iteration_, kDemoSteps));
  const auto [demo_obs, demo_act] = demos_.sample_steps(demo_of_step.reshape({-1}), generator, batch.rows);
  const auto device = agent_->device();
  const DiscriminatorData demo{demo_obs.to(device), demo_act.to(device), policy.z};
  auto shuffle = at::detail::createCPUGenerator(stream_seed(options_.seed, iteration_, kDiscriminatorBatches));
  const DiscriminatorStats disc = discriminator_trainer_->train(
      demo, policy, options_.discriminator_steps, options_.discriminator_minibatches, shuffle, batch.rows);
  last_phases_.discriminator = lap();

  ++iteration_;
  GailMetrics m;
  m.iteration = iteration_;
  m.steps = static_cast<std::int64_t>(iteration_) * batch.global_size();
  m.demo_accuracy = disc.demo_accuracy;
  m.policy_accuracy = disc.policy_accuracy;
  m.discriminator_loss = disc.loss;
  // The run's episodes and rewards: sums over this rank's, added over the ranks.
  std::vector<double> sums = {static_cast<double>(rollout.episodes.size()), 0, 0, 0,
                              rollout.rewards.sum().item<double>()};
  for (const auto& e : rollout.episodes) {
    sums[1] += e.env_return;
    sums[2] += e.length;
    sums[3] += e.terminated;
  }
  World::get().sum(sums.data(), static_cast<std::int64_t>(sums.size()));
  m.episodes = static_cast<int>(sums[0]);
  const double ended = std::max(sums[0], 1.0);
  m.env_return = sums[1] / ended;
  m.episode_length = sums[2] / ended;
  m.fall_rate = sums[3] / ended;
  m.gail_reward = sums[4] / static_cast<double>(batch.global_size());
  m.task = (*task_metrics_)(rollout, demo_of_step, demos_);
  m.kl = trpo_stats.kl;
  m.entropy = trpo_stats.entropy;
  m.value_loss = trpo_stats.value_loss_after;
  seconds_before_ += std::chrono::duration<double>(Clock::now() - start).count();
  m.seconds = seconds_before_;

  if (World::get().is_root()) {
    log_->write(row(m));
    save_checkpoint();
  }
  last_phases_.bookkeeping = lap();
  return m;
}

int GailTrainer::train(const std::function<void(const GailMetrics&)>& on_iteration) {
  const auto start = std::chrono::steady_clock::now();
  const auto minutes = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / 60.0;
  };
  // Ranks must agree to go on (a clock read differs between them): one rank's stop stops all.
  const auto go_on = [&] {
    const bool go = iteration_ < options_.iterations && (options_.minutes <= 0 || minutes() < options_.minutes);
    return World::get().sum(go ? 0.0 : 1.0) == 0.0;
  };
  int ran = 0;
  while (go_on()) {
    const GailMetrics m = iterate();
    ++ran;
    if (on_iteration) on_iteration(m);
  }
  return ran;
}

}  // namespace vaegail
