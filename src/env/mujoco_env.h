// The MuJoCo side of every environment: a model, its mjData, frame skipping, seeded resets,
// action clipping and the time limit. Tasks (walker, arm, humanoid, and GenericTaskEnv for any
// MJCF file a user brings) override the hooks; the defaults are observation qpos and qvel, zero
// reward, feature com_speed_x.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "env/env.h"
#include "env/mujoco_model.h"
#include "util/rng.h"

namespace vaegail {

// A scripted controller that acts at every physics step inside the environment's control step: a
// demonstrator whose feedback needs the physics rate (the humanoid's gait controller falls when
// its torques are held for a 0.03 s control step). Any MJCF body's controller can implement it.
class PhysicsStepController {
 public:
  virtual ~PhysicsStepController() = default;
  // Called before every physics step, after mj_step1: positions, velocities, contacts and the
  // quantities derived from them (xpos, cvel, subtree_com, qfrc_bias) are those of the state the
  // step starts from. Writes data->ctrl (the environment clips it to the action box as applied);
  // may also set data->xfrc_applied (an external push).
  virtual void control(const mjModel* model, mjData* data) = 0;
};

struct MujocoEnvOptions {
  std::string id = "mjcf";
  int frame_skip = 1;          // physics steps per control step
  int episode_length = 1000;   // control steps
  double reset_noise = 0.01;   // uniform +- on qpos and qvel of non-free joints at reset
};

class MujocoEnv : public Env {
 public:
  MujocoEnv(std::shared_ptr<const MujocoModel> model, MujocoEnvOptions options);

  const std::string& id() const override { return options_.id; }
  const BoxSpec& observation_spec() const override { return obs_spec_; }
  const BoxSpec& action_spec() const override { return act_spec_; }
  const std::vector<std::string>& feature_names() const override { return feature_names_; }
  const std::vector<std::string>& context_names() const override { return context_names_; }
  double control_timestep() const override;
  int episode_length() const override { return options_.episode_length; }
  void set_context(const std::vector<double>& context) override;
  const std::vector<double>& context() const override { return context_; }
  void reset(std::uint64_t seed) override;
  StepOutcome step(const float* action) override;
  // One control step with `controller` setting ctrl before each of its physics steps. Writes the
  // mean of the ctrl applied over the step (clipped to the action box, float[act_dim]) to
  // mean_action: the action a demonstration records, so that its files keep the shapes of
  // step()'s (an observation per control step, one action per step). Reward and termination are
  // step()'s, of mean_action. Throws for a model on the RK4 integrator, which MuJoCo cannot split
  // around a control call (mj_step1/mj_step2 then integrate by Euler).
  StepOutcome step_controlled(PhysicsStepController& controller, float* mean_action);
  // The mean ctrl `controller` would apply over the next control step from the current state,
  // as step_controlled would record it, found by running it on a copy of the simulation: this
  // environment stays where it is. The label of a demonstration recorded while noise perturbs
  // what is executed (DART, Laskey et al. 2017): what the demonstrator means from the state the
  // noise led to. The controller runs on, so pass a copy of the one that acts.
  void lookahead_controlled(PhysicsStepController& controller, float* mean_action) const;
  void observe(float* out) const override;
  void features(double* out) const override;
  int steps_taken() const override { return steps_; }
  std::unique_ptr<Env> clone() const override;

  const mjModel* model() const { return model_->get(); }
  const mjData* data() const { return data_.get(); }
  // Puts this environment in the state (qpos, qvel, act, time) of another simulation of the same
  // model, derived quantities computed (mj_forward), so that observe() reads what the task would
  // observe there: src/controller's observe() of a user's own mjData. Throws naming the model
  // when `model`'s sizes differ from this one's.
  void set_state(const mjModel* model, const mjData* data);
  // Centre-of-mass velocity of the subtree rooted at `body` (world frame, m/s).
  void subtree_velocity(int body, double out[3]) const;

 protected:
  // Hooks for tasks. Defaults describe the generic MJCF environment.
  virtual void initialize_episode(Rng& rng);
  virtual double reward(const float* action) const;
  virtual bool has_terminated() const { return false; }

  mjData* mutable_data() { return data_.get(); }

  // Tasks set their layouts in their constructors.
  BoxSpec obs_spec_, act_spec_;
  std::vector<std::string> feature_names_, context_names_;
  std::vector<double> context_;
  std::shared_ptr<const MujocoModel> model_;
  MujocoEnvOptions options_;

 private:
  // After the physics steps of a control step: the derived quantities of the new state, the
  // step count, reward and termination.
  StepOutcome finish_step(const float* action);

  // The physics steps of one control step on `d` with `controller` setting ctrl before each
  // (clipped to the action box, as applied); their mean ctrl written to mean_action.
  void run_controlled(mjData* d, PhysicsStepController& controller, float* mean_action) const;

  MjDataPtr data_;
  mutable MjDataPtr lookahead_data_;  // lookahead_controlled's copy of the simulation, made once
  int steps_ = 0;
};

}  // namespace vaegail
