// `vaegail bench physics`: how close environment rollouts with a neural policy in the loop
// come to the raw physics ceiling of the same model on this machine.
#pragma once

#include <string>

#include "env/registry.h"

namespace vaegail {

struct PhysicsBenchOptions {
  EnvRequest env;
  double seconds = 3.0;   // measuring time per configuration
  int num_envs = 16;      // environments in the VecEnv
  int threads = 1;        // threads stepping them
  int hidden = 64;        // policy: 2 tanh layers of this width
};

struct PhysicsBenchResult {
  double raw_physics_steps_per_s = 0;  // mj_step calls per second, one mjData
  double raw_control_steps_per_s = 0;  // the same in control steps (physics / frame skip)
  double vec_control_steps_per_s = 0;  // VecEnv steps per second with the policy in the loop
  double policy_fraction = 0;          // share of the loop's time spent in the policy
  double ratio() const { return vec_control_steps_per_s / raw_control_steps_per_s; }
};

PhysicsBenchResult run_physics_bench(const PhysicsBenchOptions& options);
std::string format_physics_bench(const PhysicsBenchOptions& options, const PhysicsBenchResult& result);

}  // namespace vaegail
