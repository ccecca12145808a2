// The arm's reaching experts (the paper's appendix "Jaco"): 60 independent policies, each
// trained with DDPG to reach its own random target from the same home pose.
//
// A run directory per expert, like the walker's:
//   run_dir/spec.json      the ArmExpertSpec (id, target, seed)
//   run_dir/options.json   the training options
//   run_dir/actor.pt       the actor that scored best at the periodic noise-free evaluations
//   run_dir/metrics.csv    one row per evaluation
//   run_dir/state.json     done, best return, its final grip-to-target distance and path ratio
//                          (written last)
// DDPG's replay buffer is not checkpointed: a killed expert restarts from scratch (a run takes
// well under a minute); finished experts are skipped, so a killed set resumes where it was.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "data/record.h"
#include "rl/ddpg.h"

namespace vaegail {

struct ArmExpertSpec {
  std::string id;
  std::vector<double> target;  // x, y, z (m)
  std::uint64_t seed = 0;
};

// `count` experts "reach_00", "reach_01", ... with targets drawn uniformly from the workspace
// by a stream seeded with `seed`; expert i's training seed is derived from (seed, i).
std::vector<ArmExpertSpec> arm_expert_specs(int count, std::uint64_t seed);

struct ArmExpertOptions {
  std::int64_t total_steps = 50000;
  int eval_every = 1000;  // steps between noise-free evaluations (and best-actor snapshots)
  // The reward's charge for the pose's distance from home (ArmOptions::posture_cost): with it
  // every expert resolves the arm's redundancy the same way, so nearby targets get nearby poses.
  double posture_cost = 0.0;
  DdpgOptions ddpg = default_ddpg();
  static DdpgOptions default_ddpg();
};

void to_json(nlohmann::json& j, const ArmExpertSpec& s);
void from_json(const nlohmann::json& j, ArmExpertSpec& s);
void to_json(nlohmann::json& j, const ArmExpertOptions& o);
void from_json(const nlohmann::json& j, ArmExpertOptions& o);

struct ArmExpertResult {
  double best_return = 0;
  double final_distance = 0;  // grip to target at the end of the best actor's episode (m)
  // Length of that episode's grip path over the straight distance from its start to its end:
  // 1 for a straight reach, large when the commands swing the arm back and forth.
  double path_ratio = 0;
};

// Trains until done; returns at once (with the stored result) for a finished run.
// progress(steps_done) is called after every evaluation.
ArmExpertResult train_arm_expert(const ArmExpertSpec& spec, const ArmExpertOptions& options,
                                 const std::string& run_dir,
                                 const std::function<void(std::int64_t)>& progress = nullptr);
bool arm_expert_done(const std::string& run_dir);

struct LoadedArmExpert {
  ArmExpertSpec spec;
  ArmExpertOptions options;
  ArmExpertResult result;
  std::shared_ptr<Ddpg> ddpg;  // the actor loaded; buffer empty
};
// Throws naming the directory and the missing or malformed file.
LoadedArmExpert load_arm_expert(const std::string& run_dir);

struct ArmCollectOptions {
  int episodes_per_expert = 30;  // the paper: 30 per policy
  // Gaussian noise (rad) on every executed joint command, while the demonstration records the
  // actor's own command: a deterministic actor from a fixed start would demonstrate one
  // trajectory 30 times, and a label carrying the noise would ask the VAE to predict it.
  double noise_std = 0.05;
  // When above 0, each demonstration's commands carry a constant offset (rad, per joint, drawn per
  // episode; see with_episode_offset) that the demonstration records: 30 episodes of one expert
  // then end at 30 different points around its target instead of one, so a VAE sees the whole
  // neighbourhood of every target rather than 50 isolated points.
  double offset_std = 0;
  std::uint64_t seed = 0;
  int num_envs = 10;
  std::vector<std::string> held_out;  // expert ids (the paper: the last 10 of 60)
};

// Demonstrations of reaching experts into one file; each episode's context is its expert's
// target, and held_out = 1 marks the test experts.
void collect_arm_demos(const std::vector<std::string>& expert_dirs, const std::string& out_path,
                       const ArmCollectOptions& options, Progress* progress = nullptr);

}  // namespace vaegail
