// `vaegail demos collect --task humanoid --styles FILE...`: demonstrations of the humanoid's gait
// controllers (experts/gait_controller.h), one style file per controller. The controller acts
// at every physics step; each control step records the observation and, as its action, the mean
// control applied over the step (MujocoEnv::step_controlled), so that the file has the shapes of
// every other demonstration file (137-float observations, 56-float actions, 19 features).
//
// Episode i plays style i mod K (K style files, in the order given) from the reset's perturbed
// start seeded by derive_seed(seed, i), for the environment's 334 control steps or until it
// falls; it carries context [i mod K] ("style") and expert id "SET/STYLE" (the file's "set" and
// "style", else its folder and name), so that later stages name the styles (`demos styles`).
// Clean demonstrations: no pushes, no noise (the paper's controllers' demonstrations). With
// action_noise, the noise-perturbed set of DART instead (gait_episode.h): the states the noisy
// execution visits, each with the clean controller's action from it. With a learner, DAgger's
// aggregation set: the states a mixture of learner and controller visits, labelled the same way.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "data/demos.h"
#include "env/mujoco_env.h"
#include "experts/gait_parameters.h"

namespace vaegail {

class Progress;

struct GaitDemonstrator {
  std::string label;  // "train/walk"
  GaitParameters parameters;
};

// The style of a style file, labelled by its "set" and "style" keys (else its folder and name).
GaitDemonstrator read_gait_demonstrator(const std::string& path);

struct GaitDemoOptions {
  int episodes = 250;  // in all, over the styles
  std::uint64_t seed = 0;
  int threads = 1;     // episodes recorded at once
  double action_noise = 0;  // GaitEpisodeOptions::action_noise
  // DAgger: the learner that acts in episode i of style k (GaitEpisodeOptions::learner), made once
  // per episode in the thread that records it; it acts with probability learner_share a step.
  std::function<std::function<void(const float*, float*)>(int episode, int style)> learner_for;
  double learner_share = 0;
};

// The episodes in order, and the header of the humanoid's files (context names "style").
std::vector<Episode> record_gait_demos(const std::vector<GaitDemonstrator>& styles, const GaitDemoOptions& options,
                                       DemoHeader* header, Progress* progress = nullptr);

// The style's controller for the humanoid `model`, owning what it needs: made right after a
// recorded episode's reset and stepped with MujocoEnv::step_controlled, it walks that episode
// again state for state (`render --styles`, render/episode_video.h). Its recorded actions cannot:
// they are means over each control step.
std::unique_ptr<PhysicsStepController> make_gait_demonstrator(const mjModel* model, const GaitParameters& parameters);

}  // namespace vaegail
