// `vaegail bench physics`: how close environment rollouts with a neural policy in the loop
// come to the raw physics ceiling of the same model on this machine.
#pragma once

#include <string>

#include "env/mujoco_env.h"
#include "env/registry.h"

namespace vaegail {

struct PhysicsBenchOptions {
  EnvRequest env;
  double seconds = 3.0;   // measuring time per configuration
  int num_envs = 16;      // environments in the VecEnv
  int threads = 1;        // threads stepping them
  int hidden = 64;        // policy: 2 tanh layers of this width
  int cores = 0;          // raw loops run at once for the whole machine's ceiling; 0: every core
};

struct PhysicsBenchResult {
  double raw_physics_steps_per_s = 0;  // mj_step calls per second, one mjData
  double raw_control_steps_per_s = 0;  // the same in control steps (physics / frame skip)
  // The whole machine's ceiling: one raw loop per core, all at once, their rates summed
  // (control steps/s). Cores share caches and memory bandwidth, so it is below cores x 1 core.
  int cores = 0;
  double all_core_control_steps_per_s = 0;
  double vec_control_steps_per_s = 0;  // VecEnv steps per second with the policy in the loop
  double policy_fraction = 0;          // share of the loop's time spent in the policy
  double ratio() const { return vec_control_steps_per_s / raw_control_steps_per_s; }
};

// The ceiling: mj_step on one mjData of env's model with fresh random controls each control step
// and a reset at every episode's end, as the environments see it, but none of their bookkeeping;
// physics steps per second over `seconds` on the calling thread.
double raw_physics_steps_per_s(const MujocoEnv& env, double seconds);

PhysicsBenchResult run_physics_bench(const PhysicsBenchOptions& options);
std::string format_physics_bench(const PhysicsBenchOptions& options, const PhysicsBenchResult& result);

}  // namespace vaegail
