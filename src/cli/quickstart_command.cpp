#include <cstdio>
#include <filesystem>

#include "bench/physics_bench.h"
#include "cli/commands.h"
#include "data/demo_stats.h"
#include "data/record.h"
#include "env/walker.h"
#include "util/progress.h"

namespace vaegail::cli {

namespace {

struct QuickstartOptions {
  std::string out_dir = "runs/quickstart";
  int episodes = 16;
};

void section(const char* title) { std::printf("\n== %s ==\n", title); }

void run_quickstart(const QuickstartOptions& o) {
  std::filesystem::create_directories(o.out_dir);
  WalkerEnv walker;

  section("1. the walker body and task");
  std::printf("%s: obs %d, act %d, %d steps of %g s; features:", walker.id().c_str(), walker.obs_dim(),
              walker.act_dim(), walker.episode_length(), walker.control_timestep());
  for (const auto& f : walker.feature_names()) std::printf(" %s", f.c_str());
  std::printf("\n");

  section("2. physics throughput (bench physics)");
  PhysicsBenchOptions bench;
  bench.seconds = 1.5;
  std::fputs(format_physics_bench(bench, run_physics_bench(bench)).c_str(), stdout);

  section("3. record random-policy episodes to HDF5 (env rollout)");
  const std::string path = o.out_dir + "/random_walker.h5";
  RecordRequest request;
  for (int i = 0; i < o.episodes; ++i) request.seeds.push_back(i);
  for (int i = 0; i < o.episodes; ++i) request.contexts.push_back({std::vector<double>{-1, 0, 1, 3}[i % 4]});
  request.expert_id = "random";
  Progress progress("rollout", o.episodes, "episodes");
  const auto episodes = record_episodes(walker, request, random_policy(walker, 0), &progress);
  progress.finish();
  DemoWriter writer(path, header_for(walker));
  for (const auto& e : episodes) writer.append(e);
  writer.commit();

  section("4. read it back and summarise (data info)");
  const DemoSet set = read_demos(path);
  std::fputs(format_summary(set, summarize(set)).c_str(), stdout);
  std::printf("\nquickstart done: outputs in %s\n", o.out_dir.c_str());
}

}  // namespace

void add_quickstart_command(CLI::App& app) {
  auto o = std::make_shared<QuickstartOptions>();
  CLI::App* cmd = app.add_subcommand("quickstart", "the whole walker flow at small scale (the stages that exist)");
  cmd->add_option("--out-dir", o->out_dir, "where outputs go")->capture_default_str();
  cmd->add_option("--episodes", o->episodes, "episodes to record")->check(CLI::Range(1, 1 << 30))->capture_default_str();
  cmd->callback([o] { run_quickstart(*o); });
}

}  // namespace vaegail::cli
