// Videos of demonstrations beside their imitations (render/episode_video.h), shared by
// `vaegail render`, `eval walker --videos`, `eval arm --videos`, `eval transitions --videos` and quickstart.
#pragma once

#include <CLI/CLI.hpp>
#include <torch/torch.h>

#include <cstdint>
#include <string>
#include <vector>

#include "data/demos.h"
#include "env/env.h"
#include "eval/walker_eval.h"
#include "render/episode_video.h"
#include "vae/imitation.h"

namespace vaegail::cli {

// A policy imitating demonstrations, with the latent (or an expert's condition) it gets for
// each: z [episodes, Z], row i for the i-th demonstration imitated.
struct Imitator {
  std::string caption;
  vae::LatentPolicy policy;
  torch::Tensor z;
};

// eval's policies (vae, diverse_gail, plain_gail, bc), each given the same z.
std::vector<Imitator> imitators(const std::vector<eval::NamedPolicy>& policies, const torch::Tensor& z);

// The demonstration as recorded, captioned "demonstration #I" and its context.
render::Clip demo_clip(const DemoSet& demos, int64_t episode);
// The policy rolled out from each start with its row of z [starts.size(), Z], captions[i].
std::vector<render::Clip> rollout_clips(const Env& env, const std::vector<vae::RolloutStart>& starts,
                                        const torch::Tensor& z, const vae::LatentPolicy& policy,
                                        const std::vector<std::string>& captions);
// A row per demonstration: the demonstration, then each imitator's rollout from its start.
std::vector<std::vector<render::Clip>> imitation_grid(const Env& env, const DemoSet& demos,
                                                      const std::vector<int64_t>& episodes,
                                                      const std::vector<Imitator>& imitators);

// The gait controllers of style files (experts/gait_demos.h) as the demonstrators of the
// demonstration clips (each row's first) whose expert id is a style's label ("train/walk"): those
// clips replay the controller, state for state, not its mean actions held. Throws naming the first
// demonstration whose expert id no file labels.
void attach_gait_demonstrators(std::vector<std::vector<render::Clip>>& grid, const std::vector<std::string>& style_files);

// Writes the video with a progress bar, then says where it went; a replay that departs from
// its recorded observations (a demonstration recorded with execution noise or by another
// tool) is named with by how much.
void write_video(const Env& env, const std::vector<std::vector<render::Clip>>& grid,
                 const render::VideoOptions& options, const std::string& path);

// --width, --height (of a tile), --fps, --distance, --azimuth, --elevation.
void add_video_options(CLI::App& command, render::VideoOptions& options);

}  // namespace vaegail::cli
