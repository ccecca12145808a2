// Predictive sampling (the sampling planner of mujoco_mpc; Howell et al. 2022, "Predictive
// Sampling: Real-time Behaviour Synthesis with MuJoCo"): a controller that needs no training.
// At every control step it perturbs its current plan, rolls each candidate out from the true
// state on a copy of the environment, keeps the candidate whose rollout earned the most of the
// task's own reward, and applies that plan's first action.
//
// A plan is a piecewise-linear spline of `knots` action vectors spread evenly over the
// horizon (horizon - 1 control steps from the first knot to the last): few knots keep the
// search space small (56 actuators x 4 knots for the humanoid, not 56 x 17).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "util/rng.h"

namespace vaegail {

class MujocoEnv;

struct PredictiveSamplingOptions {
  int samples = 32;           // candidate plans per control step, the unperturbed one among them
  int horizon = 17;           // control steps each candidate is rolled out (0.51 s on the humanoid)
  int knots = 4;              // spline knots over the horizon
  double noise = 0.2;         // standard deviation of each knot's perturbation (control units)
  double fall_penalty = 20;   // subtracted from a rollout that ends in a fall (the task's terminated)
  std::uint64_t seed = 0;
};

class PredictiveSampling {
 public:
  // A planner's own term added to the task's reward at each rollout step (e.g. balance).
  using Shaping = std::function<double(const MujocoEnv&)>;
  Shaping shaping;

  // `env` gives the model, the task and its context: rollouts run on a copy of it.
  PredictiveSampling(const MujocoEnv& env, PredictiveSamplingOptions options);
  ~PredictiveSampling();

  // The action to apply in `env`'s current state (act_dim floats in [-1, 1]); advances the plan
  // by one control step. `env` must be of the model the planner was made for, and its context
  // the one to plan for (read at every call).
  std::vector<float> act(const MujocoEnv& env);
  // Forget the plan (a new episode starts from a zero plan).
  void reset();
  // The current plan, [knots][act_dim] row-major.
  const std::vector<float>& plan() const { return plan_; }

  // The action of a plan at `t` control steps from its first knot (linear between knots, held
  // past the last). Plans are [knots][act_dim] row-major.
  static void plan_action(const std::vector<float>& plan, int knots, int act_dim, double spacing, double t,
                          float* out);
  // The summed reward of `plan` rolled out for the horizon from `env`'s state, less the fall
  // penalty when a step terminates (the rollout stops there).
  double score(const MujocoEnv& env, const std::vector<float>& plan);

 private:
  double spacing() const;  // control steps between knots

  PredictiveSamplingOptions options_;
  int act_dim_;
  std::unique_ptr<MujocoEnv> scratch_;
  std::vector<float> plan_;
  Rng rng_;
};

}  // namespace vaegail
