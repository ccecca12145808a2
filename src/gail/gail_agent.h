// The policy of a GAIL run, apart from its trainer (diverse_gail.h) so that the deployment
// library (src/controller) loads and runs it without the training code: the run's options as
// config.json stores them, the agent each mode builds, and its mean action as a policy.
#pragma once

#include <torch/torch.h>

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gail/gail_reward.h"
#include "gail/run_dir.h"
#include "rl/agent.h"
#include "vae/trained_vae.h"

namespace vaegail {

enum class GailMode { Diverse, Plain };
std::string to_string(GailMode mode);
GailMode parse_gail_mode(const std::string& name);  // "diverse" | "plain"; std::invalid_argument otherwise

struct GailOptions {
  GailMode mode = GailMode::Diverse;
  int iterations = 30000;   // Table 3, walker
  double minutes = 0;       // wall-clock budget of one call; 0: none
  int num_envs = 16;
  int env_threads = 1;
  int steps_per_env = 0;    // per iteration; 0: the environment's episode length
  std::vector<int> policy_hidden = {200, 100};       // Table 2, walker
  std::vector<int> critic_hidden = {200, 100};
  std::vector<int> discriminator_hidden = {100, 64};
  std::vector<int> discriminator_state_indices;      // empty: the whole observation
  double init_log_std = -1.0;                        // Table 3: initial std exp(-1)
  // Not given by the paper; the rl stage's TRPO defaults (Schulman et al.'s usual values).
  double gamma = 0.99;
  double lambda = 0.95;
  double max_kl = 0.01;
  double critic_learning_rate = 1e-3;
  int discriminator_steps = 10;                      // Table 3
  // Not in the paper: the batch of each step. 10: one pass over the iteration's samples in
  // 10 steps; 1: every step on all of them (what runs written before this option did).
  int discriminator_minibatches = 10;
  double discriminator_learning_rate = 1e-4;         // Table 3
  double reward_clip = kDefaultGailRewardClip;
  std::uint64_t seed = 0;
  std::string device = "cpu";
  // Recorded in config.json for the record; the trainer is handed the loaded data.
  std::string demos_path, vae_path;
};

// A mode in config.json is its name; an unknown name throws parse_gail_mode's error (where
// NLOHMANN_JSON_SERIALIZE_ENUM would read it as the first mode).
inline void to_json(nlohmann::json& j, GailMode mode) { j = to_string(mode); }
inline void from_json(const nlohmann::json& j, GailMode& mode) { mode = parse_gail_mode(j.get<std::string>()); }

// config.json: every field under its own name; a missing key takes the struct's default, except
// discriminator_minibatches (the adl_serializer below).
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE_WITH_DEFAULT(GailOptions, mode, iterations, minutes, num_envs, env_threads,
                                                steps_per_env, policy_hidden, critic_hidden, discriminator_hidden,
                                                discriminator_state_indices, init_log_std, gamma, lambda, max_kl,
                                                critic_learning_rate, discriminator_steps, discriminator_minibatches,
                                                discriminator_learning_rate, reward_clip, seed, device, demos_path,
                                                vae_path)

// The random stream of the run's seed that draws the agent's initial weights (the trainer's
// per-iteration streams are numbered after it).
constexpr std::uint64_t kGailInitStream = 0;

// The agent of a mode: ResidualPolicy on the frozen `vae` (diverse) or a GaussianPolicy
// (plain), a critic on the same input, and an observation normaliser frozen at the
// statistics of demo_observations [S, obs_dim]. Seeded from options.seed.
std::shared_ptr<Agent> make_gail_agent(const GailOptions& options, int obs_dim, int act_dim,
                                       const torch::Tensor& demo_observations, vae::TrajectoryVae vae);

// The trained agent of a `gail train` run (its directory, RUN/checkpoints/latest.pt or its weights
// file: gail/run_dir.h's open_run), on `device`, for evaluation. In diverse mode the agent is
// built on `vae`, whose weights loading replaces by the run's own frozen VAE's; it may be null
// for a weights file, which records the VAE's sizes. Throws naming the file.
std::shared_ptr<Agent> load_gail_agent(const std::string& run, int obs_dim, int act_dim,
                                       vae::TrajectoryVae vae, torch::Device device);

// A diverse-GAIL weights file's frozen VAE, built to the sizes it records (untrained until the
// agent is loaded on it); null for a trainer checkpoint, which records none.
vae::TrajectoryVae recorded_vae(const RunFile& run);

// An agent's mean action as a policy to roll out (vae/imitation.h); an agent trained without a
// latent (plain GAIL, behaviour cloning) ignores z.
vae::LatentPolicy agent_mean_policy(std::shared_ptr<Agent> agent);

}  // namespace vaegail

// Runs made before discriminator_minibatches existed trained every discriminator step on the
// full batch: their config.json lacks the key and reads as 1, not as the default 10.
NLOHMANN_JSON_NAMESPACE_BEGIN
template <>
struct adl_serializer<vaegail::GailOptions> {
  static void to_json(json& j, const vaegail::GailOptions& o) { vaegail::to_json(j, o); }
  static void from_json(const json& j, vaegail::GailOptions& o) {
    vaegail::from_json(j, o);
    if (!j.contains("discriminator_minibatches")) o.discriminator_minibatches = 1;
  }
};
NLOHMANN_JSON_NAMESPACE_END
