#include "cli/imitation_video.h"

#include <cstdio>
#include <fmt/format.h>
#include <map>
#include <stdexcept>

#include "experts/gait_demos.h"
#include "util/progress.h"

namespace vaegail::cli {

namespace {

// A replay whose observations depart by more than this from the recorded ones is reported
// (float observations of an exact replay agree to ~1e-6).
constexpr double kReplayTolerance = 1e-3;

std::string policy_caption(const std::string& name) {
  static const std::map<std::string, std::string> captions{
      {"vae", "VAE"}, {"diverse_gail", "diverse GAIL"}, {"plain_gail", "plain GAIL"}, {"bc", "BC"}};
  const auto it = captions.find(name);
  return it == captions.end() ? name : it->second;
}

}  // namespace

std::vector<Imitator> imitators(const std::vector<eval::NamedPolicy>& policies, const torch::Tensor& z) {
  std::vector<Imitator> out;
  for (const auto& p : policies) out.push_back({policy_caption(p.name), p.policy, z});
  return out;
}

render::Clip demo_clip(const DemoSet& demos, int64_t episode) {
  if (episode < 0 || episode >= static_cast<int64_t>(demos.episodes.size()))
    throw std::invalid_argument(demos.path + ": no episode " + std::to_string(episode) + " (it has " +
                                std::to_string(demos.episodes.size()) + ", from 0)");
  const Episode& e = demos.episodes[episode];
  std::string caption = "demonstration #" + std::to_string(episode);
  // A style's index means nothing on screen; its controller's label ("train/walk") does.
  if (demos.header.context_names == std::vector<std::string>{"style"} && !e.expert_id.empty())
    return {caption + "\n" + e.expert_id, e};
  for (size_t k = 0; k < e.context.size() && k < demos.header.context_names.size(); ++k)
    caption += fmt::format("{}{} {:.3g}", k ? ", " : "\n", demos.header.context_names[k], e.context[k]);
  return {caption, e};
}

std::vector<render::Clip> rollout_clips(const Env& env, const std::vector<vae::RolloutStart>& starts,
                                        const torch::Tensor& z, const vae::LatentPolicy& policy,
                                        const std::vector<std::string>& captions) {
  vae::ImitationOptions options;
  options.speed_feature.clear();  // rendered, not measured: any task will do
  auto outcomes = vae::roll_out_latent_policy(env, starts, z, policy, options);
  std::vector<render::Clip> clips;
  for (size_t i = 0; i < outcomes.size(); ++i) clips.push_back({captions.at(i), std::move(outcomes[i].episode)});
  return clips;
}

std::vector<std::vector<render::Clip>> imitation_grid(const Env& env, const DemoSet& demos,
                                                      const std::vector<int64_t>& episodes,
                                                      const std::vector<Imitator>& imitators) {
  std::vector<std::vector<render::Clip>> grid;
  for (int64_t e : episodes) grid.push_back({demo_clip(demos, e)});
  const auto starts = vae::rollout_starts(demos, episodes);
  for (const auto& imitator : imitators) {
    const std::vector<std::string> captions(episodes.size(), imitator.caption);
    auto clips = rollout_clips(env, starts, imitator.z, imitator.policy, captions);
    for (size_t r = 0; r < clips.size(); ++r) grid[r].push_back(std::move(clips[r]));
  }
  return grid;
}

void attach_gait_demonstrators(std::vector<std::vector<render::Clip>>& grid, const std::vector<std::string>& style_files) {
  std::map<std::string, GaitParameters> styles;
  for (const auto& path : style_files) {
    GaitDemonstrator style = read_gait_demonstrator(path);
    styles.emplace(style.label, std::move(style.parameters));
  }
  for (auto& row : grid) {
    render::Clip& demo = row.at(0);
    const auto it = styles.find(demo.episode.expert_id);
    if (it == styles.end())
      throw std::invalid_argument(demo.caption.substr(0, demo.caption.find('\n')) + ": its expert id '" +
                                  demo.episode.expert_id + "' is none of the --styles files' labels");
    demo.demonstrator = [parameters = it->second](const mjModel* model) {
      return make_gait_demonstrator(model, parameters);
    };
  }
}

void write_video(const Env& env, const std::vector<std::vector<render::Clip>>& grid,
                 const render::VideoOptions& options, const std::string& path) {
  Progress progress("render", render::video_frames(grid), "frames");
  const auto reports = render::write_episode_video(env, grid, options, path, &progress);
  progress.finish();
  for (const auto& r : reports)
    if (r.max_observation_error > kReplayTolerance)
      std::fprintf(stderr, "vaegail: note: %s: the replay departs from the recorded observations by up to %.3g "
                   "(recorded with execution noise, by another tool, or by a physics-step demonstrator: --styles?)\n",
                   r.caption.substr(0, r.caption.find('\n')).c_str(), r.max_observation_error);
  std::printf("wrote %s\n", path.c_str());
}

void add_video_options(CLI::App& command, render::VideoOptions& options) {
  // yuv420p halves the colour planes: odd sizes are refused when parsing, before any work.
  const CLI::Validator even([](std::string& value) { return std::stoi(value) % 2 ? "must be even" : ""; }, "EVEN");
  command.add_option("--width", options.tile_width, "pixels across each tile; the video is a grid of tiles")
      ->check(CLI::Range(16, 4096))->check(even)->capture_default_str();
  command.add_option("--height", options.tile_height, "pixels down each tile")
      ->check(CLI::Range(16, 4096))->check(even)->capture_default_str();
  command.add_option("--fps", options.fps, "frames per second, one frame per control step (0: real time)")
      ->check(CLI::Range(0, 1000))->capture_default_str();
  command.add_option("--distance", options.camera.distance,
                     "camera distance from the body (m; 0: 3x the body's radius)")
      ->check(CLI::Range(0.0, 1000.0))->capture_default_str();
  command.add_option("--azimuth", options.camera.azimuth, "camera azimuth (degrees; 90: from the side)")
      ->capture_default_str();
  command.add_option("--elevation", options.camera.elevation, "camera elevation (degrees; negative: from above)")
      ->check(CLI::Range(-90.0, 90.0))->capture_default_str();
}

}  // namespace vaegail::cli
