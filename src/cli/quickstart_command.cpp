// `vaegail quickstart`: the walker flow at small scale on the published demonstrations and VAE,
// as the same command lines a user would type (each is echoed before it runs).
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <stdexcept>

#include "bench/physics_bench.h"
#include "cli/app.h"
#include "cli/commands.h"
#include "cli/task_options.h"
#include "env/walker.h"

namespace vaegail::cli {

namespace {

struct QuickstartOptions {
  std::string out_dir = "runs/quickstart";
  std::string demos = kPublishedWalkerDemos;
  std::string vae = kPublishedWalkerVae;
  double gail_minutes = 4, plain_minutes = 2;
  int bc_epochs = 5;
  int per_expert = 3;
  int envs = 8;
  int video_episode = 260;  // 1 m/s: the published VAE and diverse GAIL both stay up on it
};

void section(const char* title) { std::printf("\n== %s ==\n", title); }

void require_file(const std::string& path, const char* what) {
  if (!std::filesystem::exists(path))
    throw std::invalid_argument(path + ": no such " + what + " (run quickstart from the repository root)");
}

void run_quickstart(const QuickstartOptions& o) {
  ensure_published_walker_demos(o.demos);
  require_file(o.demos, "demonstration file");
  require_file(o.vae, "VAE checkpoint");
  std::filesystem::create_directories(o.out_dir);
  const WalkerEnv walker;
  const std::string demos = " --demos " + o.demos, vae = " --vae " + o.vae;
  const std::string envs = " --envs " + std::to_string(o.envs);

  section("1. the walker body and task");
  std::printf("%s: obs %d, act %d, %d steps of %g s; features:", walker.id().c_str(), walker.obs_dim(),
              walker.act_dim(), walker.episode_length(), walker.control_timestep());
  for (const auto& f : walker.feature_names()) std::printf(" %s", f.c_str());
  std::printf("\n");

  section("2. physics throughput");
  PhysicsBenchOptions bench;
  bench.seconds = 1.5;
  std::fputs(format_physics_bench(bench, run_physics_bench(bench)).c_str(), stdout);

  section("3. the published demonstrations (expert speeds per target)");
  run_command_line("data info " + o.demos);

  section("4. the published VAE: embed every demonstration, classify held-out experts by 5-NN");
  const std::string embeddings = o.out_dir + "/embeddings.csv";
  run_command_line("vae embed --checkpoint " + o.vae + demos + " --out " + embeddings);
  run_command_line("vae knn --embeddings " + embeddings + " --k 5");

  section("5. fine-tune with diverse GAIL, and train the baselines (small scale)");
  run_command_line("gail train --mode diverse" + demos + vae + " --run-dir " + o.out_dir + "/diverse_gail --minutes " +
                   fmt::format("{:g}", o.gail_minutes) + envs);
  run_command_line("gail train --mode plain" + demos + " --run-dir " + o.out_dir + "/plain_gail --minutes " +
                   fmt::format("{:g}", o.plain_minutes) + envs);
  run_command_line("bc train" + demos + " --run-dir " + o.out_dir + "/bc --epochs " + std::to_string(o.bc_epochs));

  section("6. evaluate: imitate demonstrations, compare speeds (the paper's Figure 4)");
  run_command_line("eval walker" + demos + vae + " --gail " + o.out_dir + "/diverse_gail --plain " + o.out_dir +
                   "/plain_gail --bc " + o.out_dir + "/bc --per-expert " + std::to_string(o.per_expert) + envs +
                   " --out-dir " + o.out_dir + "/eval");

  section("7. see it: a demonstration beside its VAE and fine-tuned imitations (headless rendering)");
  run_command_line("render" + demos + " --episodes " + std::to_string(o.video_episode) + vae + " --gail " + o.out_dir +
                   "/diverse_gail --out " + o.out_dir + "/walker.mp4");
  std::printf("\nquickstart done: outputs in %s\n", o.out_dir.c_str());
}

}  // namespace

void add_quickstart_command(CLI::App& app) {
  auto o = std::make_shared<QuickstartOptions>();
  CLI::App* cmd = app.add_subcommand("quickstart", "the whole walker flow at small scale on the published data and VAE");
  cmd->add_option("--out-dir", o->out_dir, "where outputs go")->capture_default_str();
  cmd->add_option("--demos", o->demos, "demonstration file")->capture_default_str();
  cmd->add_option("--vae", o->vae, "trained VAE run (directory, checkpoint or weights.pt)")->capture_default_str();
  cmd->add_option("--gail-minutes", o->gail_minutes, "diverse-GAIL fine-tuning time")
      ->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--plain-minutes", o->plain_minutes, "plain-GAIL training time")
      ->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--bc-epochs", o->bc_epochs, "behaviour-cloning epochs")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  cmd->add_option("--per-expert", o->per_expert, "demonstrations per expert in the evaluation")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  cmd->add_option("--envs", o->envs, "environments for GAIL rollouts and the evaluation")
      ->check(CLI::Range(1, 1 << 16))->capture_default_str();
  cmd->add_option("--video-episode", o->video_episode, "the demonstration in walker.mp4 (an episode index)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  cmd->callback([o] { run_quickstart(*o); });
}

}  // namespace vaegail::cli
