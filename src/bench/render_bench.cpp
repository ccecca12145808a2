#include "bench/render_bench.h"

#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <unistd.h>

#include "data/record.h"
#include "env/mujoco_env.h"
#include "render/frame_renderer.h"
#include "render/mp4_writer.h"

namespace vaegail {

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

RenderBenchResult run_render_bench(const RenderBenchOptions& options) {
  EnvRequest request = options.env;
  request.terminate_on_fall = false;
  const auto env = make_env(request);
  auto* mujoco = dynamic_cast<MujocoEnv*>(env.get());
  if (!mujoco) throw render::RenderError("environment '" + env->id() + "' is not a MuJoCo one: nothing to render");
  RecordRequest episode;
  episode.seeds = {0};
  episode.num_envs = 1;
  const Episode random = record_episodes(*env, episode, random_policy(*env, 0)).front();

  render::FrameRenderer renderer(mujoco->model(), {1, 1, options.width, options.height});
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("vaegail_bench_render_" + std::to_string(getpid()) + ".mp4")).string();
  RenderBenchResult result;
  result.gl_renderer = renderer.gl_renderer();
  result.frames = std::min(options.frames, random.length() + 1);
  {
    render::Mp4Writer video(path, {options.width, options.height, 30});
    env->reset(random.seed);
    for (int f = 0; f < result.frames; ++f) {
      if (f > 0) env->step(random.actions.data() + static_cast<size_t>(f - 1) * env->act_dim());
      auto start = std::chrono::steady_clock::now();
      renderer.draw(0, 0, *mujoco->data(), "bench render");
      const auto& frame = renderer.read();
      result.draw_seconds += seconds_since(start);
      start = std::chrono::steady_clock::now();
      video.write(frame.data());
      result.encode_seconds += seconds_since(start);
    }
    const auto start = std::chrono::steady_clock::now();
    video.finish();
    result.encode_seconds += seconds_since(start);
  }
  std::filesystem::remove(path);
  return result;
}

std::string format_render_bench(const RenderBenchOptions& options, const RenderBenchResult& r) {
  return fmt::format(
      "render {} at {}x{}, {} frames on {}\n"
      "  draw (mjv_updateScene + mjr_render + mjr_readPixels): {:7.1f} frames/s\n"
      "  encode (yuv420p + libx264 veryfast):                  {:7.1f} frames/s\n"
      "  draw + encode:                                        {:7.1f} frames/s\n",
      options.env.task, options.width, options.height, r.frames, r.gl_renderer, r.draw_fps(), r.encode_fps(),
      r.total_fps());
}

}  // namespace vaegail
