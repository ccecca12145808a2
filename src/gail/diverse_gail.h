// The adversarial stage, Algorithm 1 of the paper, and its plain-GAIL baseline.
//
// One iteration:
//   1. every environment, at the start of each of its episodes, draws a training
//      demonstration τ_j, sets the environment's context to τ_j's (the walker's target speed)
//      and, in `diverse` mode, draws z_j ~ q(· | τ_j) (one reparameterised sample of the
//      VAE posterior, μ and σ precomputed per demonstration) as the episode's condition;
//   2. the policy runs `steps_per_env` steps in each environment (default: one episode length,
//      Algorithm 1's one trajectory per draw); rewards r = min(-log(1 - D(x, a | z_j)), clip);
//   3. TRPO updates the policy (and fits the critic) on GAE advantages;
//   4. the discriminator takes `discriminator_steps` Adam steps: every policy step
//      (x̂_t, â_t, z_j) against a uniformly drawn step (x_t, a_t) of τ_j with the same z_j,
//      each step on 1/`discriminator_minibatches` of these pairs (see DiscriminatorTrainer).
// `plain` mode: no z anywhere; a GaussianPolicy from scratch and an unconditional D.
//
// The agent's observation normaliser is fixed to the training demonstrations' statistics
// (the residual policy needs a fixed normaliser, see residual_policy.h; plain mode uses the
// same for a like-for-like baseline).
//
// Run directory:
//   run_dir/config.json              GailOptions (a rerun must agree, except on iterations,
//                                    minutes, device, env_threads)
//   run_dir/metrics.csv              one row per completed iteration (columns: kGailMetricColumns)
//   run_dir/checkpoints/latest.pt    agent (policy incl. the frozen VAE, critic, normaliser),
//                                    discriminator, the Adam states of discriminator and critic,
//                                    the iteration count,
//                                    one file written atomically after every iteration
//
// Ranks (`mpirun -np K vaegail gail train ...`, util/world.h): num_envs counts the run's
// environments; each rank steps num_envs / K of them, and every sum, mean, shuffle and draw is
// made over the run's batch (rl/distributed.h), so K ranks train what one process with all
// num_envs environments trains, to float rounding, and a run may resume with another K. Rank 0
// alone writes config, metrics and checkpoints; every rank reads the checkpoint (across
// machines the run directory must be on a shared file system).
//
// Reproducibility: every random stream of iteration k (demonstration draws, z noise, the
// environments' reset seeds, action noise, TRPO's critic minibatches, the discriminator's demo
// steps) is derived from (seed, k), and nothing else carries over between iterations except
// what the checkpoint holds. So a run killed after iteration k and resumed equals the
// uninterrupted run (same thread counts). The price: each iteration starts fresh episodes
// (with the default steps_per_env an iteration is exactly one episode per environment
// anyway). The critic's Adam state carries over between iterations and is checkpointed; a
// checkpoint written before it was kept resumes with a fresh one.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "data/demos.h"
#include "env/env.h"
#include "env/vec_env.h"
#include "gail/discriminator.h"
#include "gail/gail_agent.h"
#include "gail/gail_demos.h"
#include "gail/gail_reward.h"
#include "gail/task_metrics.h"
#include "rl/distributed.h"
#include "rl/agent.h"
#include "rl/trpo.h"
#include "util/csv_log.h"
#include "util/run_lock.h"
#include "vae/imitation.h"
#include "vae/trajectory_vae.h"

namespace vaegail {

// One metrics.csv row.
struct GailMetrics {
  int iteration = 0;          // 1-based, completed
  std::int64_t steps = 0;     // environment steps so far
  int episodes = 0;           // episodes that ended in this iteration
  double demo_accuracy = 0, policy_accuracy = 0, discriminator_loss = 0;  // before its update
  double gail_reward = 0;     // mean per step
  double env_return = 0;      // mean over ended episodes (the task's own reward, context = the demo's)
  double episode_length = 0, fall_rate = 0;
  Metrics task;               // the task's own by column name (task_metrics.h), e.g. the walker's speed_error
  double kl = 0, entropy = 0, value_loss = 0;
  double seconds = 0;         // since the run began, summed over resumed calls
};
extern const std::vector<std::string> kGailMetricColumns;

// Where an iteration's wall-clock went (for `bench gail`; not logged).
struct GailPhaseSeconds {
  double rollout = 0;        // environments and policy sampling, discriminator rewards
  double policy_update = 0;  // TRPO step and critic fit
  double discriminator = 0;  // demonstration steps drawn, discriminator Adam steps
  double bookkeeping = 0;    // metrics row, CSV, atomic checkpoint
  double total() const { return rollout + policy_update + discriminator + bookkeeping; }
  GailPhaseSeconds& operator+=(const GailPhaseSeconds& o);
};

// The paper's settings for a body (appendix, Tables 2 and 3), on top of GailOptions' own defaults
// (which are the walker's): "walker", or "humanoid": policy and critic (300, 200, 100),
// discriminator (300, 200), initial policy std 0.1, 100000 iterations (the discriminator's
// learning rate 1e-4 and 10 steps are the walker's too). Either way the discriminator sees
// `env`'s discriminator_observation() (the humanoid's root and end effectors; the walker's whole
// observation). Throws std::invalid_argument naming an unknown preset.
GailOptions gail_preset(const std::string& name, const Env& env);
// The preset named after the environment's task when there is one ("humanoid"), else "walker".
std::string default_gail_preset(const Env& env);

class GailTrainer {
 public:
  // `vae` is required in diverse mode and ignored in plain mode. Checks that the
  // demonstrations, the environment and the VAE agree (std::invalid_argument, one line),
  // creates or resumes run_dir, which it holds for its life (util/run_lock.h: a second trainer
  // on it is refused).
  GailTrainer(const DemoSet& demos, vae::TrajectoryVae vae, const Env& prototype, GailOptions options,
              std::string run_dir);

  // Iterates until options.iterations are done or options.minutes have passed in this call;
  // returns the iterations it ran.
  int train(const std::function<void(const GailMetrics&)>& on_iteration = nullptr);
  // One iteration of Algorithm 1, then the metrics row and the checkpoint.
  GailMetrics iterate();

  int iteration() const { return iteration_; }
  const GailPhaseSeconds& last_phase_seconds() const { return last_phases_; }
  const GailOptions& options() const { return options_; }
  Agent& agent() { return *agent_; }
  Discriminator& discriminator() { return *discriminator_; }
  std::string checkpoint_path() const { return run_dir_ + "/checkpoints/latest.pt"; }
  std::string metrics_path() const { return run_dir_ + "/metrics.csv"; }

 private:
  void save_checkpoint() const;
  void load_checkpoint();

  GailOptions options_;
  std::string run_dir_;
  RunLock lock_;
  GailDemos demos_;
  EnvSlice slice_;  // this rank's share of the run's num_envs environments
  std::unique_ptr<VecEnv> envs_;
  int steps_per_env_ = 0;
  std::unique_ptr<GailTaskMetrics> task_metrics_;
  std::shared_ptr<Agent> agent_;
  std::shared_ptr<Discriminator> discriminator_;
  std::unique_ptr<DiscriminatorTrainer> discriminator_trainer_;
  std::unique_ptr<Trpo> trpo_;
  std::shared_ptr<GailReward> reward_;
  std::unique_ptr<CsvLog> log_;
  int iteration_ = 0;
  double seconds_before_ = 0;  // run time of earlier calls, from the checkpoint
  GailPhaseSeconds last_phases_;
};

}  // namespace vaegail
