#include "render/episode_video.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "env/mujoco_env.h"
#include "render/mp4_writer.h"
#include "render/png_writer.h"
#include "util/progress.h"

namespace vaegail::render {

namespace {

// One clip being replayed: its environment copy and how far it has got.
class Replay {
 public:
  Replay(const Env& prototype, const Clip& clip) : clip_(clip), env_(prototype.clone()) {
    mujoco_ = dynamic_cast<MujocoEnv*>(env_.get());
    if (!mujoco_) throw RenderError("environment '" + prototype.id() + "' is not a MuJoCo one: nothing to render");
    const Episode& e = clip.episode;
    const int act_dim = env_->act_dim(), obs_dim = env_->obs_dim();
    if (e.actions.size() != static_cast<size_t>(e.length()) * act_dim)
      throw DataError(clip.caption + ": actions hold " + std::to_string(e.actions.size()) + " values, not " +
                      std::to_string(e.length()) + " steps x " + std::to_string(act_dim));
    has_observations_ = e.observations.size() == static_cast<size_t>(e.length() + 1) * obs_dim;
    if (!e.context.empty()) env_->set_context(e.context);
    env_->reset(e.seed);
    if (clip.demonstrator) {
      demonstrator_ = clip.demonstrator(mujoco_->model());
      mean_action_.resize(act_dim);
    }
    observation_.resize(obs_dim);
    compare();
  }

  // Steps the next recorded action (or the demonstrator for as long); false once every action has
  // been stepped.
  bool advance() {
    if (step_ >= clip_.episode.length()) return false;
    if (demonstrator_)
      mujoco_->step_controlled(*demonstrator_, mean_action_.data());
    else
      env_->step(clip_.episode.actions.data() + static_cast<size_t>(step_) * env_->act_dim());
    ++step_;
    compare();
    return true;
  }

  const mjData& data() const { return *mujoco_->data(); }
  std::string caption() const {
    if (step_ < clip_.episode.length()) return clip_.caption;
    const auto& ends = clip_.episode.terminations;
    return clip_.caption + (!ends.empty() && ends.back() ? "\nfell at step " : "\nended at step ") +
           std::to_string(step_);
  }
  ReplayReport report() const { return {clip_.caption, step_, max_error_}; }

 private:
  void compare() {
    if (!has_observations_) return;
    env_->observe(observation_.data());
    const float* recorded = clip_.episode.observations.data() + static_cast<size_t>(step_) * observation_.size();
    for (size_t i = 0; i < observation_.size(); ++i)
      max_error_ = std::max(max_error_, static_cast<double>(std::abs(observation_[i] - recorded[i])));
  }

  const Clip& clip_;
  std::unique_ptr<Env> env_;
  MujocoEnv* mujoco_ = nullptr;
  std::unique_ptr<PhysicsStepController> demonstrator_;
  std::vector<float> mean_action_;
  bool has_observations_ = false;
  int step_ = 0;
  double max_error_ = 0;
  std::vector<float> observation_;
};

// The still: the asked-for frames copied side by side as the video passes them, written once
// the video is done. Frame indices are checked before any frame is drawn.
class StillStrip {
 public:
  StillStrip(const VideoOptions& options, int frames, const FrameLayout& layout)
      : path_(options.still_path), frame_width_(layout.width()), height_(layout.height()) {
    if (path_.empty()) return;
    if (options.still_frames.empty()) throw RenderError(path_ + ": no frame asked for");
    for (int f : options.still_frames) {
      const int frame = f < 0 ? frames / 2 : f;
      if (frame >= frames)
        throw RenderError(path_ + ": frame " + std::to_string(frame) + " of a video of " + std::to_string(frames) +
                          " frames");
      frames_.push_back(frame);
    }
    rgb_.resize(static_cast<size_t>(width()) * height_ * 3);
  }

  // Copies the frame `f` (rgb, top row first) into every place of the strip that asks for it.
  void take(int f, const std::uint8_t* rgb) {
    const size_t row_bytes = static_cast<size_t>(frame_width_) * 3;
    for (size_t k = 0; k < frames_.size(); ++k) {
      if (frames_[k] != f) continue;
      for (int y = 0; y < height_; ++y)
        std::copy_n(rgb + y * row_bytes, row_bytes,
                    rgb_.data() + (static_cast<size_t>(y) * width() + k * frame_width_) * 3);
    }
  }

  void write() const {
    if (!path_.empty()) write_png(path_, width(), height_, rgb_.data());
  }

 private:
  int width() const { return static_cast<int>(frames_.size()) * frame_width_; }

  std::string path_;
  int frame_width_, height_;
  std::vector<int> frames_;
  std::vector<std::uint8_t> rgb_;
};

}  // namespace

int video_frames(const std::vector<std::vector<Clip>>& grid) {
  int steps = 0;
  for (const auto& row : grid)
    for (const auto& clip : row) steps = std::max(steps, clip.episode.length());
  return steps + 1;
}

int video_fps(const Env& env, const VideoOptions& options) {
  return options.fps > 0 ? options.fps : std::max(1, static_cast<int>(std::lround(1.0 / env.control_timestep())));
}

std::vector<ReplayReport> write_episode_video(const Env& prototype, const std::vector<std::vector<Clip>>& grid,
                                              const VideoOptions& options, const std::string& path,
                                              Progress* progress) {
  FrameLayout layout{static_cast<int>(grid.size()), 0, options.tile_width, options.tile_height};
  for (const auto& row : grid) layout.cols = std::max(layout.cols, static_cast<int>(row.size()));
  if (layout.cols == 0) throw RenderError(path + ": no episode to render");

  std::vector<std::vector<std::unique_ptr<Replay>>> replays(grid.size());
  for (size_t r = 0; r < grid.size(); ++r)
    for (const auto& clip : grid[r]) replays[r].push_back(std::make_unique<Replay>(prototype, clip));
  const auto* mujoco = dynamic_cast<const MujocoEnv*>(&prototype);
  FrameRenderer renderer(mujoco->model(), layout, options.camera);
  Mp4Writer video(path, {layout.width(), layout.height(), video_fps(prototype, options)});

  const int frames = video_frames(grid);
  StillStrip still(options, frames, layout);
  for (int f = 0; f < frames; ++f) {
    for (int r = 0; r < layout.rows; ++r)
      for (int c = 0; c < layout.cols; ++c) {
        if (c >= static_cast<int>(replays[r].size())) {
          renderer.clear(r, c);
          continue;
        }
        Replay& replay = *replays[r][c];
        if (f > 0) replay.advance();
        renderer.draw(r, c, replay.data(), replay.caption());
      }
    video.write(renderer.read().data());
    still.take(f, renderer.read().data());
    if (progress) progress->advance();
  }
  video.finish();
  still.write();

  std::vector<ReplayReport> reports;
  for (const auto& row : replays)
    for (const auto& replay : row) reports.push_back(replay->report());
  return reports;
}

}  // namespace vaegail::render
