// The default task of any MJCF body that has no task class of its own (`--task my_body.xml`).
// What a task class would hard-code is read from the MJCF, mujoco_mpc style, under <custom>:
//
//   <numeric name="vaegail_episode_length" data="400"/>  control steps per episode (default 1000)
//   <numeric name="vaegail_frame_skip" data="4"/>        physics steps per control step (default 1)
//   <text    name="vaegail_fall_body" data="torso"/>     the body whose height says it fell
//   <numeric name="vaegail_fall_height" data="0.8"/>     fallen below this world z (m); default 0
//   <numeric name="vaegail_context_NAME" data="1.5"/>    a context entry NAME and its default
//
// Command-line values (--episode-length, --frame-skip) override the MJCF's.
//
// Observation: qpos then qvel, every joint (MujocoEnv's layout). Action: the actuators, clipped
// to their ctrlrange (or [-1, 1]). Reset: keyframe 0 when the MJCF has one, else qpos0; then
// +-0.01 uniform noise on the non-free joints.
// Features, in this order:
//   com_speed              x velocity of the centre of mass of the first body's subtree (m/s)
//   BODY_height, fallen    with vaegail_fall_body: its world z, and 1 when below the fall height
//   sensor:NAME[k]         every named <sensor>, one feature per component ("[k]" when several)
//   site:NAME:x|y|z        world position of every named <site>
// Context: the MJCF's vaegail_context_* entries, then any further names the options give (a
// demonstration file's context attributes); it is recorded with the episodes and changes nothing
// in the physics: a task whose dynamics or reward depend on context needs a task class.
// Reward: 0 (GAIL supplies its own; a task reward for expert training needs a task class).
// Termination: when fallen (unless terminate_on_fall is off); truncation at the episode length.
#pragma once

#include <string>
#include <vector>

#include "env/mujoco_env.h"

namespace vaegail {

struct GenericTaskOptions {
  int frame_skip = 0;      // 0: the MJCF's vaegail_frame_skip, else 1
  double control_timestep = 0;  // > 0 with frame_skip 0: the frame skip giving this step (a file's)
  int episode_length = 0;  // 0: the MJCF's vaegail_episode_length, else 1000
  bool terminate_on_fall = true;
  std::vector<std::string> context_names;  // appended to the MJCF's (names it has are skipped)
};

class GenericTaskEnv : public MujocoEnv {
 public:
  // The environment id is the model's source (the MJCF path). Throws naming the model when a
  // vaegail_* entry is malformed or names a body the model lacks.
  GenericTaskEnv(std::shared_ptr<const MujocoModel> model, GenericTaskOptions options);

  StepOutcome step(const float* action) override;
  void features(double* out) const override;
  std::unique_ptr<Env> clone() const override;
  std::string body_mjcf() const override { return model_->xml(); }
  bool fallen() const;

 protected:
  void initialize_episode(Rng& rng) override;
  bool has_terminated() const override { return options_generic_.terminate_on_fall && fallen(); }

 private:
  GenericTaskOptions options_generic_;
  int fall_body_ = -1;  // -1: the body cannot fall
  double fall_height_ = 0.0;
  std::vector<int> sensor_values_;  // sensordata index of each sensor feature
  std::vector<int> site_values_;    // site_xpos index of each site feature
};

}  // namespace vaegail
