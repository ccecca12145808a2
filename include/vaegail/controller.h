// A trained vaegail policy in your own simulation loop (issue 40 item 5).
//
//   auto c = vaegail::Controller::load_vae("run/checkpoints/latest.pt", "walker");
//   std::vector<float> z = c.embed(demo_states);          // one demonstration -> its embedding
//   for (...) {                                           // your loop, your mjModel / mjData
//     std::vector<float> a = c.act(c.observe(m, d), z);   // the policy's mean action
//     std::copy(a.begin(), a.end(), d->ctrl);
//     for (int k = 0; k < frame_skip; ++k) mj_step(m, d); // frame_skip = control_timestep() / m->opt.timestep
//   }
//
// This header uses the standard library only: LibTorch, HDF5 and the training code stay inside
// libvaegail_controller (find_package(vaegail), target_link_libraries(app vaegail::controller)),
// and MuJoCo's types are only declared, so a program that never calls observe() needs no MuJoCo.
//
// Layouts (row-major float, raw units as the training environment produced them):
//   observation  [obs_dim]               the task's observation (src/env/<task>.h documents it)
//   states       [num_states * obs_dim]  a demonstration's observations x_1 .. x_{T+1}
//   z            [latent_dim]            the embedding; empty for a policy without one
//   action       [act_dim]               to write into mjData::ctrl (MuJoCo clamps it to
//                                        ctrlrange, as the training environment did)
//
// Errors throw std::exception subclasses whose what() is one line naming the file or argument.
// A Controller is movable, not copyable; act() and embed() may run on several threads at once,
// observe() may not (it computes on one scratch simulation).
#pragma once

#include <memory>
#include <string>
#include <vector>

struct mjModel_;  // MuJoCo's mjModel and mjData (<mujoco/mujoco.h>)
struct mjData_;

// The library is built with hidden symbols; the Controller is what it exports.
#define VAEGAIL_CONTROLLER_API __attribute__((visibility("default")))

namespace vaegail {

class VAEGAIL_CONTROLLER_API Controller {
 public:
  // `task` is the environment the policy was trained in: a built-in task ("walker", "arm",
  // "humanoid") or the path of the MJCF file of your own body. It gives the observation and
  // action sizes (checked against the policy's), observe() and control_timestep().

  // Each loader takes a run as training left it or as `vaegail export` ships it: the run
  // directory, its checkpoint (RUN/checkpoints/latest.pt) or its weights file (RUN/weights.pt).

  // The VAE policy of a `vaegail vae train` run. The action decoder's mean acts; the encoder
  // embeds.
  static Controller load_vae(const std::string& vae_run, const std::string& task);
  // A `vaegail gail train` run. Diverse mode acts with the fine-tuned residual policy and embeds
  // with the VAE it was fine-tuned on, whose weights the run's own file holds. A weights file
  // records that VAE's sizes; for a checkpoint they come from `vae_checkpoint` (a VAE run), or
  // when empty from the run's recorded vae_path. Plain mode has no embedding.
  static Controller load_gail(const std::string& run, const std::string& task,
                              const std::string& vae_checkpoint = "");
  // A `vaegail bc train` run: no embedding.
  static Controller load_bc(const std::string& run, const std::string& task);

  Controller(Controller&&) noexcept;
  Controller& operator=(Controller&&) noexcept;
  ~Controller();

  int obs_dim() const;
  int act_dim() const;
  int latent_dim() const;  // 0: the policy takes no embedding (plain GAIL, BC)
  // Simulated seconds per action in training: the task's frame skip times the model's timestep.
  double control_timestep() const;

  // The mean of the encoder's posterior q(z | x_1 .. x_{T+1}) for one demonstration, the z the
  // paper's one-shot imitation conditions on; empty when latent_dim() is 0. Reads states only.
  std::vector<float> embed(const std::vector<float>& states) const;
  // The policy's mean action for one observation and embedding.
  std::vector<float> act(const std::vector<float>& observation, const std::vector<float>& z) const;
  // The task's observation of the state in `data` (qpos, qvel, act of a simulation of the same
  // model; its derived fields need not be current). Part of the API because the built-in tasks
  // compute observations from kinematics (the walker's torso height and pitch, the arm's grip
  // position) that must match training exactly; an MJCF body without a task class observes
  // qpos then qvel.
  std::vector<float> observe(const mjModel_* model, const mjData_* data);

 private:
  struct Impl;
  explicit Controller(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace vaegail
