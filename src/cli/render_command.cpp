// `vaegail render`: demonstrations, and policies imitating them, to an MP4 (a row per
// demonstration, a column per source); `vaegail bench render`: frames per second of drawing
// and encoding.
#include <torch/torch.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "bench/render_bench.h"
#include "cli/commands.h"
#include "cli/eval_policies.h"
#include "cli/imitation_video.h"
#include "cli/task_options.h"
#include "experts/expert_trainer.h"
#include "gail/diverse_gail.h"
#include "vae/vae_trainer.h"

namespace vaegail::cli {

namespace fs = std::filesystem;

namespace {

struct RenderFlags {
  std::string demos, task, vae, gail, plain, bc, expert, out, device = "cpu";
  std::vector<int64_t> episodes;
  std::vector<std::string> styles;  // the humanoid's gait controllers that recorded the demonstrations
  int columns = 0;                  // demonstrations alone, this many to a row
  render::VideoOptions video;
};

// The single-clip rows of demonstrations alone, `columns` to a row.
std::vector<std::vector<render::Clip>> wrap_rows(std::vector<std::vector<render::Clip>> grid, int columns) {
  std::vector<std::vector<render::Clip>> wrapped;
  for (size_t i = 0; i < grid.size(); ++i) {
    if (i % columns == 0) wrapped.emplace_back();
    wrapped.back().push_back(std::move(grid[i].at(0)));
  }
  return wrapped;
}

// A PPO expert of `experts train` (experts/walker/ID) from each demonstration's start; its
// condition input, when it has one, is the demonstration's context (its target or style).
Imitator expert_imitator(const std::string& run_dir, const DemoSet& demos, const std::vector<int64_t>& episodes) {
  const LoadedExpert expert = load_expert(run_dir);
  const int condition_dim = expert.spec.conditioned() ? expert.spec.condition_dim() : 0;
  torch::Tensor conditions = torch::zeros({static_cast<int64_t>(episodes.size()), condition_dim});
  for (size_t i = 0; i < episodes.size() && condition_dim > 0; ++i) {
    const auto& context = demos.episodes[episodes[i]].context;
    if (context.empty()) throw std::invalid_argument(demos.path + ": episode " + std::to_string(episodes[i]) +
                                                     " has no context to condition expert " + expert.spec.id + " on");
    conditions[i] = torch::tensor(expert.spec.condition_for(context[0]));
  }
  return {"expert", agent_mean_policy(expert.agent), conditions};
}

void run_render(const RenderFlags& f) {
  torch::NoGradGuard no_grad;
  const auto device = parse_device(f.device);
  if (!f.gail.empty() && f.vae.empty()) throw std::invalid_argument("--gail needs --vae (diverse GAIL's policy takes the VAE's z)");
  if (!f.vae.empty() && !fs::exists(f.vae)) throw std::invalid_argument(f.vae + ": no such VAE checkpoint");
  const DemoSet demos = read_demos(f.demos);
  check_demo_task(demos, f.task);
  for (int64_t e : f.episodes) demo_clip(demos, e);  // every index checked before any work
  vae::TrajectoryVae model{nullptr};
  if (!f.vae.empty()) {
    model = vae::load_trained_vae(f.vae, device);
    model->eval();
  }
  const auto env = model ? demo_env(demos, model) : demo_env(demos);
  const auto z = model ? vae::encode_episodes(model, demos, f.episodes)
                       : torch::zeros({static_cast<int64_t>(f.episodes.size()), 1});
  auto sources = imitators(load_policies(model, *env, {f.gail, f.plain, f.bc}, device), z);
  if (!f.expert.empty()) sources.push_back(expert_imitator(f.expert, demos, f.episodes));
  if (f.columns > 0 && !sources.empty())
    throw std::invalid_argument("--columns lays out demonstrations alone; beside policies each row is one demonstration");
  auto grid = imitation_grid(*env, demos, f.episodes, sources);
  if (!f.styles.empty()) attach_gait_demonstrators(grid, f.styles);
  if (f.columns > 0) grid = wrap_rows(std::move(grid), f.columns);
  if (fs::path(f.out).has_parent_path()) fs::create_directories(fs::path(f.out).parent_path());
  write_video(*env, grid, f.video, f.out);
}

void add_render(CLI::App& app) {
  auto f = std::make_shared<RenderFlags>();
  CLI::App* c = app.add_subcommand(
      "render", "demonstrations, and the policies imitating them, to an MP4 video: a row per demonstration, a column "
                "per source (headless: Mesa's software OpenGL, H.264)");
  c->add_option("--demos", f->demos, "demonstration file (.h5)")->required();
  c->add_option("--episodes", f->episodes, "episode indices in the file, one row each (e.g. --episodes 3 17)")
      ->required()->check(CLI::NonNegativeNumber);
  add_demo_task_option(*c, f->task);
  c->add_option("--vae", f->vae, "VAE run (directory, checkpoint or weights.pt): adds the VAE policy's imitation (and encodes for --gail)");
  c->add_option("--gail", f->gail, "diverse-GAIL run (directory, checkpoint or weights.pt) on the same VAE: adds its imitation");
  c->add_option("--plain", f->plain, "plain-GAIL run (directory, checkpoint or weights.pt): adds its rollout from the same start");
  c->add_option("--bc", f->bc, "behaviour-cloning run (directory, checkpoint or weights.pt): adds its rollout from the same start");
  c->add_option("--expert", f->expert, "expert run directory (experts/walker/ID): adds its rollout from the same "
                                       "start, conditioned on the demonstration's context");
  c->add_option("--styles", f->styles, "the humanoid's gait-controller style files (configs/humanoid_styles/): "
                                       "demonstrations they recorded are replayed by the controller itself, whose "
                                       "torques change at every physics step, not by its mean actions held")
      ->check(CLI::ExistingFile);
  c->add_option("--columns", f->columns, "demonstrations alone (no policies): this many side by side per row")
      ->check(CLI::Range(1, 64));
  c->add_option("--out", f->out, "the video (.mp4)")->required();
  add_video_options(*c, f->video);
  c->add_option("--still", f->video.still_path,
                "also write frames of the video as a PNG (a page's still, or a strip through time)");
  c->add_option("--still-frame", f->video.still_frames,
                "which frames --still shows, left to right (0: the start; -1: the middle; e.g. 0 40 80: a strip)")
      ->check(CLI::Range(-1, 1 << 20))->capture_default_str();
  add_device_option(*c, f->device);
  c->callback([f] { run_render(*f); });
}

struct RenderBenchFlags {
  TaskOptions task;
  RenderBenchOptions bench;
};

void add_bench_render(CLI::App& bench) {
  auto f = std::make_shared<RenderBenchFlags>();
  CLI::App* c = bench.add_subcommand("render", "frames per second of offscreen drawing (llvmpipe) and H.264 encoding");
  add_task_options(*c, f->task);
  c->add_option("--width", f->bench.width, "frame width (even)")->check(CLI::Range(16, 8192))->capture_default_str();
  c->add_option("--height", f->bench.height, "frame height (even)")->check(CLI::Range(16, 8192))->capture_default_str();
  c->add_option("--frames", f->bench.frames, "frames drawn and encoded (at most an episode's)")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  c->callback([f] {
    f->bench.env = f->task.request();
    std::fputs(format_render_bench(f->bench, run_render_bench(f->bench)).c_str(), stdout);
  });
}

}  // namespace

void add_render_commands(CLI::App& app) {
  add_render(app);
  add_bench_render(*app.get_subcommand("bench"));  // add_bench_commands runs first
}

}  // namespace vaegail::cli
