// The trajectory VAE of paper section 3.1: encoder q(z | x_{1:T}), action decoder
// pi(a_t | x_t, z) and state decoder p(x_{t+1} | x_t, z), with the per-trajectory loss
//
//   L(tau) = -[ sum_t log pi(a_t | x_t, z) + log p(x_{t+1} | x_t, z) ] + kl_weight * KL(q || N(0, I))
//
// with one reparameterised sample z ~ q per trajectory (kl_weight = 1: the negative ELBO).
//
// Shapes at the boundary (raw, unnormalised units; B trajectories of T steps):
//   states  [B, T+1, D] float   x_1 .. x_{T+1}
//   actions [B, T, A]   float   a_1 .. a_T
//   mask    [B, T]      bool/0-1, optional: step t is real; a prefix of each row. Trajectory b
//           then has states 0..len_b (the state after its last action included); the rest is
//           padding, ignored (even NaN).
//   z       [B, Z]
//
// Normalisation: states and actions are standardised per dimension with the training set's
// mean and std, stored as buffers (state_mean, state_std, action_mean, action_std) so that a
// checkpoint is self-contained. Every model sees and every likelihood is reported in the
// NORMALISED space: a density of raw states differs by the constant -sum_d log state_std_d
// per step (action_log_jacobian()/state_log_jacobian() give these constants).
//
// With config.action_relative_to_state, the modelled action is a_t - x_t[k] (raw units) and
// action_mean() adds x_t[k] back; the action normalisation and likelihood are those of the
// difference.
#pragma once

#include <torch/torch.h>

#include "vae/action_decoder.h"
#include "vae/state_decoder.h"
#include "vae/trajectory_encoder.h"
#include "vae/vae_config.h"

namespace vaegail::vae {

// Per-trajectory means over the batch; each a scalar tensor (total keeps the graph).
struct VaeLoss {
  torch::Tensor total;       // action_nll + state_nll + kl_weight * kl
  torch::Tensor action_nll;  // -sum_t log pi(a_t | x_t, z)
  torch::Tensor state_nll;   // -sum_t log p(x_{t+1} | x_t, z)
  torch::Tensor kl;          // KL(q(z | x) || N(0, I))
  torch::Tensor per_trajectory;  // [B] total of each trajectory
};

// The decoders' negative log-likelihoods of each trajectory given its z: [B] each.
struct DecoderNll {
  torch::Tensor action;  // -sum_t log pi(a_t | x_t, z)
  torch::Tensor state;   // -sum_t log p(x_{t+1} | x_t, z)
};

class TrajectoryVaeImpl : public torch::nn::Module {
 public:
  explicit TrajectoryVaeImpl(const VaeConfig& config);

  // Per-dimension mean and std over the real steps (std floored: a constant dimension gets 1).
  void fit_normalization(const torch::Tensor& states, const torch::Tensor& actions,
                         const torch::Tensor& mask = {});
  void set_normalization(const torch::Tensor& state_mean, const torch::Tensor& state_std,
                         const torch::Tensor& action_mean, const torch::Tensor& action_std);

  // The loss of a batch. noise [B, Z] ~ N(0, I) for the reparameterised z; encoder_noise
  // [B, T+1, D] ~ N(0, I) for the encoder's input (read only when training with
  // encoder_input_noise > 0). Undefined: drawn with torch's default generator on the model's
  // device. A trainer passes both so that a row's draws do not depend on the rows beside it.
  VaeLoss loss(const torch::Tensor& states, const torch::Tensor& actions,
               const torch::Tensor& mask = {}, const torch::Tensor& noise = {},
               const torch::Tensor& encoder_noise = {});

  // The decoders' likelihood of a batch (as loss()) at a given z [B, Z] instead of a sample of q.
  DecoderNll decoder_nll(const torch::Tensor& states, const torch::Tensor& actions, const torch::Tensor& z,
                         const torch::Tensor& mask = {});

  // q(z | states): states [B, S, D] raw, mask [B, S] over states (optional).
  EncoderOutput encode(const torch::Tensor& states, const torch::Tensor& state_mask = {});
  // The action decoder's mean in raw units: state [..., D] raw, z [..., Z] -> [..., A] raw.
  torch::Tensor action_mean(const torch::Tensor& state, const torch::Tensor& z);
  // Draws x_{t+1} [N, D] raw from the state decoder given x_t [N, D] raw and z [N, Z].
  torch::Tensor sample_next_state(const torch::Tensor& state, const torch::Tensor& z,
                                  c10::optional<at::Generator> generator = c10::nullopt);

  torch::Tensor normalize_states(const torch::Tensor& states) const;
  // What the action decoder reads of normalised states x [..., D]: x itself, or with
  // config.policy_state_std_floor > 0 each component rescaled to that floor on its std.
  torch::Tensor policy_input(const torch::Tensor& x) const;
  // Sets config.policy_state_std_floor (the action decoder then wants retraining: vae refit-policy).
  void set_policy_state_std_floor(double floor);
  torch::Tensor normalize_actions(const torch::Tensor& actions) const;
  // log|d normalised / d raw| per step: add to a normalised log-density to get the raw one.
  double state_log_jacobian() const;
  double action_log_jacobian() const;

  // The actions the action decoder models, in raw units: actions [B, T, A] given states
  // [B, T+1, D] (see action_relative_to_state).
  torch::Tensor modelled_actions(const torch::Tensor& states, const torch::Tensor& actions) const;

  const VaeConfig& config() const { return config_; }
  TrajectoryEncoder& encoder() { return encoder_; }
  ActionDecoder& action_decoder() { return action_decoder_; }
  StateDecoder& state_decoder() { return state_decoder_; }

 private:
  VaeConfig config_;
  TrajectoryEncoder encoder_{nullptr};
  ActionDecoder action_decoder_{nullptr};
  StateDecoder state_decoder_{nullptr};
  torch::Tensor state_mean_, state_std_, action_mean_, action_std_;

  // A batch normalised, its padding zeroed; the masks undefined without a mask.
  struct Prepared {
    torch::Tensor x, a, step_mask, state_mask;
  };
  Prepared prepare(const torch::Tensor& states, const torch::Tensor& actions, const torch::Tensor& mask) const;
  DecoderNll decoder_nll(const Prepared& prepared, const torch::Tensor& z);

  // x[..., k_j] for each action component j: [..., A] raw; a scalar 0 without offsets.
  torch::Tensor action_offset(const torch::Tensor& state) const;
  // The k_j (CPU, int64; not a buffer, so that checkpoints keep their layout); undefined
  // without offsets.
  torch::Tensor offset_index_;
  // What the encoder reads of normalised states x [B, S, D]: the encoder_state_indices
  // components (all without) of x + encoder_input_noise * noise (noise [B, S, D] or undefined:
  // none), zero on padding.
  torch::Tensor encoder_input(const torch::Tensor& x, const torch::Tensor& state_mask, const torch::Tensor& noise) const;
  torch::Tensor encoder_index_;  // the encoder_state_indices as offset_index_; undefined: all
};
TORCH_MODULE(TrajectoryVae);

// The state mask [B, T+1] of a step mask [B, T]: state 0 and the state after every real step.
torch::Tensor state_mask_from_step_mask(const torch::Tensor& step_mask);

}  // namespace vaegail::vae
