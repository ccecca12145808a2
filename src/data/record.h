// Rolls a policy out in an environment and records the episodes in the demonstration format.
// Episodes run on a pool of environment copies; the policy sees a batch of the environments
// still running at each step.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "data/demos.h"
#include "env/env.h"

namespace vaegail {

class Progress;

// Fills actions [n, act_dim] for observations [n, obs_dim]; episodes[i] says which requested
// episode row i belongs to, and steps[i] how many steps that episode has taken.
using BatchPolicy = std::function<void(int n, const float* observations, const int* episodes,
                                       const int* steps, float* actions)>;

struct RecordRequest {
  std::vector<std::uint64_t> seeds;             // one per episode: its reset seed
  std::vector<std::vector<double>> contexts;    // one per episode, or empty for the env's own
  std::string expert_id;
  int num_envs = 8;     // environments stepped together
  int num_threads = 1;  // threads stepping them
  // When above 0, each environment executes the policy's action plus Gaussian noise of this std
  // (clipped to the action box; one stream per episode, seeded by (execution_noise_seed,
  // episode)) while the episode records the action before the noise: the demonstration's label
  // is what the policy meant in the state its perturbed execution led to.
  double execution_noise_std = 0;
  std::uint64_t execution_noise_seed = 0;
};

DemoHeader header_for(const Env& env);

// Episodes come back in request order, each with its seed, context and per-step features;
// the episode's mean of every feature (over the states its actions reached) is stored as an
// attribute "mean_<feature>".
std::vector<Episode> record_episodes(const Env& prototype, const RecordRequest& request,
                                     const BatchPolicy& policy, Progress* progress = nullptr);

// Uniform random actions within the action bounds; each episode draws from its own stream
// seeded by (seed, episode), so the recording does not depend on batching.
BatchPolicy random_policy(const Env& env, std::uint64_t seed);
BatchPolicy zero_policy(const Env& env);

// The policy's actions plus an offset that is constant over an episode and drawn per episode
// and per component from N(0, std^2) (stream seeded by (seed, episode)), clipped to the box: a
// family of demonstrators around one policy, each of which ends its episodes somewhere else.
// Unlike execution noise, the offset is part of the recorded action, and a whole trajectory
// shows it.
BatchPolicy with_episode_offset(BatchPolicy policy, const BoxSpec& box, double std, std::uint64_t seed);

}  // namespace vaegail
