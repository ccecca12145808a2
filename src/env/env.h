// The environment interface every body and task implements (walker, arm, humanoid, any MJCF).
//
// Conventions:
//   observation  float[obs_dim]   layout named by observation_spec().names
//   action       float[act_dim]   clipped to action_spec() bounds by the environment
//   features     double[n]        named per-step measurements (speed, torso height, fallen...)
//   context      double[k]        task parameters that persist across resets (target speed...)
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace vaegail {

// A box of named real values: the observation or action layout.
struct BoxSpec {
  std::vector<std::string> names;
  std::vector<double> low;
  std::vector<double> high;
  int dim() const { return static_cast<int>(names.size()); }
};

struct StepOutcome {
  double reward = 0.0;
  bool terminated = false;  // the task ended (fell): no bootstrapping past it
  bool truncated = false;   // the time limit ended the episode
  bool done() const { return terminated || truncated; }
};

class Env {
 public:
  virtual ~Env() = default;

  virtual const std::string& id() const = 0;
  virtual const BoxSpec& observation_spec() const = 0;
  virtual const BoxSpec& action_spec() const = 0;
  virtual const std::vector<std::string>& feature_names() const = 0;
  virtual const std::vector<std::string>& context_names() const = 0;
  virtual double control_timestep() const = 0;
  virtual int episode_length() const = 0;

  // Context is kept across resets; set it before reset(). Throws on a wrong size.
  virtual void set_context(const std::vector<double>& context) = 0;
  virtual const std::vector<double>& context() const = 0;

  // The same seed (and context) gives the same initial state, bit for bit.
  virtual void reset(std::uint64_t seed) = 0;
  virtual StepOutcome step(const float* action) = 0;
  virtual void observe(float* out) const = 0;
  virtual void features(double* out) const = 0;
  // Control steps since the last reset.
  virtual int steps_taken() const = 0;

  // The observation components the adversarial stage's discriminator sees unless told otherwise
  // (indices into observation(), ascending); empty: the whole observation. A body declares a
  // subset when its full state lets a discriminator tell demonstrations from imitations by
  // details that say nothing about the behaviour (the humanoid's 112 joint angles and velocities).
  virtual std::vector<int> discriminator_observation() const { return {}; }

  // The MJCF text of a body the registry rebuilds from its text (a user's file: GenericTaskEnv),
  // which demonstration files store; empty for the built-in tasks, rebuilt by name.
  virtual std::string body_mjcf() const { return {}; }

  // An independent copy in its initial configuration (same model, context and options).
  virtual std::unique_ptr<Env> clone() const = 0;

  int obs_dim() const { return observation_spec().dim(); }
  int act_dim() const { return action_spec().dim(); }
  std::vector<float> observation() const {
    std::vector<float> out(obs_dim());
    observe(out.data());
    return out;
  }
};

}  // namespace vaegail
