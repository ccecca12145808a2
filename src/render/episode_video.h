// Episodes to an MP4: each episode is replayed in its environment (reset with its seed and
// context, then its recorded actions stepped one by one: MuJoCo is deterministic, so the replay
// passes through the recorded states) and drawn as one tile of a grid, one frame per control
// step. A demonstration file stores observations, not MuJoCo states, and the walker's leave out
// where it stands; its actions and seed are what rebuild the motion. The replay is checked
// against the recorded observations, so an episode that cannot be replayed exactly (recorded
// with execution noise, or imported from another tool) says by how much it departs.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "data/demos.h"
#include "env/env.h"
#include "env/mujoco_env.h"
#include "render/frame_renderer.h"

namespace vaegail {
class Progress;
}

namespace vaegail::render {

// An episode and the caption of its tile. The episode needs its seed, context (empty: the
// environment's own) and actions [T, act_dim]; observations [T+1, obs_dim], when present,
// are compared with the replay's.
//
// An episode recorded by a controller acting at every physics step (MujocoEnv::step_controlled:
// the humanoid's gait controllers) stores, as its actions, the mean control of each step; held
// for a whole control step they leave its path within about a second. Such a clip carries the
// demonstrator, made for the replay's model right after the reset, and the replay runs it again
// (deterministic physics: the same states, checked against the recorded observations).
using DemonstratorFactory = std::function<std::unique_ptr<PhysicsStepController>(const mjModel* model)>;

struct Clip {
  std::string caption;
  Episode episode;
  DemonstratorFactory demonstrator;  // empty: the recorded actions are stepped
};

struct VideoOptions {
  int tile_width = 320, tile_height = 240;  // pixels per tile, even
  int fps = 0;  // 0: real time, 1 / the control step (rounded): 40 for the walker
  CameraOptions camera;
  // Also a PNG (render/png_writer.h), the still a page shows: the frames `still_frames` side by
  // side, left to right in that order (one frame, or a strip of a motion through time), each
  // the whole grid; 0 is the initial states, a negative index the video's middle frame. Empty
  // path: none.
  std::string still_path;
  std::vector<int> still_frames = {-1};
};

struct ReplayReport {
  std::string caption;
  int steps = 0;  // control steps replayed
  // Largest |replayed - recorded| over every observation component and step; 0 without
  // recorded observations.
  double max_observation_error = 0;
};

// grid[r][c] is the clip of row r, column c; the frame has as many columns as the longest row
// (the cells a shorter row lacks stay black) and runs until the longest episode ends (an ended
// episode holds its last state, captioned "ended"). Throws RenderError (one line) for an
// environment that is not a MuJoCo one or an empty grid, DataError naming the clip for an
// episode that does not fit the environment. `progress` advances one per frame.
std::vector<ReplayReport> write_episode_video(const Env& prototype, const std::vector<std::vector<Clip>>& grid,
                                              const VideoOptions& options, const std::string& path,
                                              Progress* progress = nullptr);

// The frames a grid's video has: the longest episode's steps + 1.
int video_frames(const std::vector<std::vector<Clip>>& grid);
// options.fps, or real time for `env`.
int video_fps(const Env& env, const VideoOptions& options);

}  // namespace vaegail::render
