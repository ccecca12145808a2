// `vaegail gail train` (the adversarial stage, diverse or plain GAIL) and `vaegail bc train`
// (the behaviour-cloning baseline).
#include <torch/torch.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <stdexcept>

#include "bench/gail_bench.h"
#include "cli/commands.h"
#include "cli/task_options.h"
#include "env/registry.h"
#include "gail/behavior_cloning.h"
#include "gail/diverse_gail.h"
#include "util/atomic_file.h"
#include "util/progress.h"
#include "util/world.h"
#include "vae/vae_trainer.h"

namespace vaegail::cli {

namespace {

// ---- gail train -----------------------------------------------------------------------
struct GailFlags {
  std::string mode = "diverse", demos, vae, run_dir, task, preset;
  GailOptions options;
};

// The VAE a mode needs (none in plain mode), after checking the flags agree with the mode.
vae::TrajectoryVae mode_vae(GailFlags& f) {
  parse_device(f.options.device);
  f.options.mode = parse_gail_mode(f.mode);
  f.options.demos_path = f.demos;
  const bool diverse = f.options.mode == GailMode::Diverse;
  if (diverse && f.vae.empty()) throw std::invalid_argument("--mode diverse needs --vae (a VAE run)");
  if (!diverse && !f.vae.empty()) throw std::invalid_argument("--mode plain takes no --vae");
  f.options.vae_path = f.vae;
  if (!diverse) return vae::TrajectoryVae(nullptr);
  if (!std::filesystem::exists(f.vae)) throw std::invalid_argument(f.vae + ": no such VAE checkpoint");
  return vae::load_trained_vae(f.vae, torch::Device(f.options.device));
}

// The run's options: the preset's (by default the one of the demonstrations' body, gail_preset),
// then every flag given on `command`'s line.
GailOptions preset_options(const GailFlags& f, const CLI::App& command, const Env& env) {
  const GailOptions preset = gail_preset(f.preset.empty() ? default_gail_preset(env) : f.preset, env);
  GailOptions o = f.options;  // the flags, the struct's defaults where none was given
  o.policy_hidden = preset.policy_hidden;
  o.critic_hidden = preset.critic_hidden;
  o.discriminator_hidden = preset.discriminator_hidden;
  o.init_log_std = preset.init_log_std;
  const auto given = [&command](const char* flag) {
    const CLI::Option* option = command.get_option_no_throw(flag);
    return option && option->count() > 0;
  };
  if (!given("--iterations")) o.iterations = preset.iterations;
  if (!given("--disc-steps")) o.discriminator_steps = preset.discriminator_steps;
  if (!given("--disc-lr")) o.discriminator_learning_rate = preset.discriminator_learning_rate;
  if (!given("--disc-state-indices")) o.discriminator_state_indices = preset.discriminator_state_indices;
  return o;
}

void add_mode_options(CLI::App& c, GailFlags& f) {
  c.add_option("--mode", f.mode, "diverse: VAE-conditioned policy and discriminator; plain: GAIL without z")
      ->check(CLI::IsMember({"diverse", "plain"}))->capture_default_str();
  c.add_option("--preset", f.preset,
               "the paper's sizes and settings for a body (Tables 2-3): walker, or humanoid (policy and critic "
               "(300, 200, 100), discriminator (300, 200), initial std 0.1, 100000 iterations); default: the "
               "demonstrations' body's; the discriminator sees the body's own subset of the observation "
               "(humanoid: root and end effectors, 112..136; walker: all)")
      ->check(CLI::IsMember({"walker", "humanoid"}));
  c.add_option("--vae", f.vae, "VAE run (directory, checkpoints/latest.pt or weights.pt); diverse mode");
  c.add_option("--envs", f.options.num_envs, "environments, one demonstration each per episode")
      ->check(CLI::Range(1, 1 << 16))->capture_default_str();
  c.add_option("--env-threads", f.options.env_threads, "threads stepping them")
      ->check(CLI::Range(1, 256))->capture_default_str();
  c.add_option("--disc-minibatches", f.options.discriminator_minibatches,
               "each discriminator step on 1/N of the iteration's samples (1: all of them)")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  add_device_option(c, f.options.device);
}

void run_gail(GailFlags f, const CLI::App& command) {
  const vae::TrajectoryVae model = mode_vae(f);
  const DemoSet demos = read_demos(f.demos);
  check_demo_task(demos, f.task);
  const auto env = demo_env(demos);
  f.options = preset_options(f, command, *env);
  GailTrainer trainer(demos, model, *env, f.options, f.run_dir);
  if (trainer.iteration() > 0) std::printf("resuming %s after iteration %d\n", f.run_dir.c_str(), trainer.iteration());
  std::fflush(stdout);
  Progress progress("gail " + f.mode, f.options.iterations, "it");
  progress.resume(trainer.iteration());
  if (f.options.minutes > 0) progress.set_time_budget(60 * f.options.minutes);
  trainer.train([&](const GailMetrics& m) {
    std::string line = fmt::format("D acc {:.2f}/{:.2f}  reward {:.2f}  return {:.1f}  falls {:.2f}", m.demo_accuracy,
                                   m.policy_accuracy, m.gail_reward, m.env_return, m.fall_rate);
    for (const auto& [name, value] : m.task) line += fmt::format("  {} {:.2f}", name, value);
    progress.set_status(line);
    progress.set(m.iteration);
  });
  progress.finish();
  std::printf("%d/%d iterations\nmetrics: %s\ncheckpoint: %s\n", trainer.iteration(), f.options.iterations,
              trainer.metrics_path().c_str(), trainer.checkpoint_path().c_str());
}

void add_gail_train(CLI::App& gail) {
  auto f = std::make_shared<GailFlags>();
  GailOptions& o = f->options;
  CLI::App* c = gail.add_subcommand(
      "train", "adversarial imitation (Algorithm 1); rerun with the same --run-dir to resume or extend");
  add_mode_options(*c, *f);
  c->add_option("--demos", f->demos, "demonstration file (.h5)")->required();
  c->add_option("--run-dir", f->run_dir, "config.json, metrics.csv, checkpoints/latest.pt")->required();
  add_demo_task_option(*c, f->task);
  c->add_option("--iterations", o.iterations,
                "train until this many iterations in total (default: the preset's, Table 3: walker 30000, humanoid 100000)")
      ->check(CLI::Range(1, 1 << 30));
  c->add_option("--minutes", o.minutes, "stop after this many minutes of this call (0: no limit)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  c->add_option("--steps-per-env", o.steps_per_env, "steps per environment per iteration (0: one episode)")
      ->check(CLI::Range(0, 1 << 30))->capture_default_str();
  c->add_option("--disc-steps", o.discriminator_steps, "discriminator Adam steps per iteration (Table 3, both presets)")
      ->check(CLI::Range(0, 1 << 20))->capture_default_str();
  c->add_option("--disc-lr", o.discriminator_learning_rate, "discriminator learning rate (Table 3, both presets)")
      ->check(CLI::PositiveNumber)->capture_default_str();
  c->add_option("--disc-state-indices", o.discriminator_state_indices,
                "observation components the discriminator sees (default: the body's subset, Env::discriminator_observation: "
                "humanoid 112..136, others all)");
  c->add_option("--reward-clip", o.reward_clip, "upper bound of the reward -log(1 - D)")
      ->check(CLI::PositiveNumber)->capture_default_str();
  c->add_option("--max-kl", o.max_kl, "TRPO's bound on the mean KL per update")->check(CLI::PositiveNumber)->capture_default_str();
  c->add_option("--seed", o.seed, "initialisation, demonstration draws, z, environments, noise")->capture_default_str();
  c->callback([f, c] { run_gail(*f, *c); });
}

// ---- bc train -------------------------------------------------------------------------
struct BcFlags {
  std::string demos, run_dir;
  BcOptions options;
};

void run_bc(BcFlags f) {
  parse_device(f.options.device);
  f.options.demos_path = f.demos;
  const DemoSet demos = read_demos(f.demos);
  Progress progress("bc", f.options.epochs, "epochs");
  train_bc(demos, f.options, f.run_dir, [&](const BcEpoch& e) {
    progress.set_status(fmt::format("nll train {:.3f}  val {:.3f}", e.train_nll, e.val_nll));
    progress.set(e.epoch);
  });
  progress.finish();
  std::printf("metrics: %s/metrics.csv\ncheckpoint: %s/checkpoints/latest.pt\n", f.run_dir.c_str(), f.run_dir.c_str());
}

void add_bc_train(CLI::App& bc) {
  auto f = std::make_shared<BcFlags>();
  BcOptions& o = f->options;
  CLI::App* c = bc.add_subcommand("train", "behaviour cloning: a Gaussian MLP policy by maximum likelihood, no latent");
  c->add_option("--demos", f->demos, "demonstration file (.h5)")->required();
  c->add_option("--run-dir", f->run_dir, "config.json, metrics.csv, checkpoints/latest.pt")->required();
  c->add_option("--epochs", o.epochs, "train until this many epochs in total")->check(CLI::Range(1, 1 << 30))->capture_default_str();
  c->add_option("--batch-size", o.batch_size, "(x, a) pairs per step")->check(CLI::Range(1, 1 << 24))->capture_default_str();
  c->add_option("--lr", o.learning_rate, "Adam learning rate")->check(CLI::PositiveNumber)->capture_default_str();
  c->add_option("--seed", o.seed, "initialisation, shuffling and the validation split")->capture_default_str();
  add_device_option(*c, o.device);
  c->callback([f] { run_bc(*f); });
}

// ---- bench gail -----------------------------------------------------------------------
struct GailBenchFlags {
  GailFlags gail;
  GailBenchOptions bench;
  std::string json;
};

// The task's demonstrations where --demos is not given: the published walker's, or the
// humanoid's training set of scripts/reproduce/humanoid.sh.
std::string bench_demos(const GailFlags& f) {
  const std::string demos = !f.demos.empty()           ? f.demos
                            : f.task == "humanoid"     ? kHumanoidTrainDemos
                                                       : kPublishedWalkerDemos;
  if (demos == kHumanoidTrainDemos && !std::filesystem::exists(demos))
    throw std::invalid_argument(demos + ": no such file (scripts/reproduce/humanoid.sh demos makes it)");
  ensure_published_walker_demos(demos);
  return demos;
}

void add_bench_gail(CLI::App& bench) {
  auto f = std::make_shared<GailBenchFlags>();
  CLI::App* c = bench.add_subcommand(
      "gail", "seconds per fine-tuning iteration by phase, env steps/s against the all-core physics ceiling of the "
              "same body (default: the task's demonstrations and VAE, and its preset)");
  add_mode_options(*c, f->gail);
  c->add_option("--task", f->gail.task,
                "walker (default: " + kPublishedWalkerDemos + ", " + kPublishedWalkerVae + ") or humanoid (" +
                    kHumanoidTrainDemos + ", " + kHumanoidVae + ")")
      ->check(CLI::IsMember({"walker", "humanoid"}))->default_str("walker");
  c->add_option("--demos", f->gail.demos, "demonstration file (.h5); default: the task's (the VAE: the file's body's)");
  c->add_option("--iterations", f->bench.iterations, "timed iterations (after one warm-up)")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  c->add_option("--physics-seconds", f->bench.physics_seconds, "measuring time per physics ceiling")
      ->check(CLI::Range(0.1, 3600.0))->capture_default_str();
  c->add_option("--json", f->json, "also write the figures to this JSON file (scripts/bench/gail_ranks.sh reads it)");
  c->callback([f, c] {
    GailFlags flags = f->gail;
    flags.demos = bench_demos(flags);
    const DemoSet demos = read_demos(flags.demos);
    check_demo_task(demos, flags.task);
    if (flags.mode == "diverse" && flags.vae.empty())  // the VAE of the demonstrations' body
      flags.vae = demos.header.env_id == "humanoid" ? kHumanoidVae : kPublishedWalkerVae;
    const vae::TrajectoryVae model = mode_vae(flags);
    GailBenchOptions options = f->bench;
    options.env = demo_env_request(demos);
    options.gail = preset_options(flags, *c, *make_env(options.env));
    const GailBenchResult result = run_gail_bench(options, demos, model);
    std::fputs(format_gail_bench(options, result).c_str(), stdout);
    if (!f->json.empty() && World::get().is_root())
      write_file_atomically(f->json, gail_bench_json(options, result).dump(2) + "\n");
  });
}

}  // namespace

void add_gail_commands(CLI::App& app) {
  add_bench_gail(*app.get_subcommand("bench"));  // add_bench_commands runs first
  CLI::App* gail = app.add_subcommand("gail", "the adversarial stage: diverse GAIL and its plain baseline");
  gail->require_subcommand(1);
  add_gail_train(*gail);
  CLI::App* bc = app.add_subcommand("bc", "the behaviour-cloning baseline");
  bc->require_subcommand(1);
  add_bc_train(*bc);
}

}  // namespace vaegail::cli
