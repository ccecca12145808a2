// Action decoder pi_alpha(a_t | x_t, z) (paper section 3.1): an MLP (tanh hidden units) on
// (x_t, z) giving the mean and log-std of a diagonal Gaussian over a_t, per step; or, with
// state_dependent_std false, a learned log-std per action component shared by all steps.
#pragma once

#include <torch/torch.h>

#include <vector>

namespace vaegail::vae {

struct ActionDistribution {
  torch::Tensor mean;     // [..., A]
  torch::Tensor log_std;  // [..., A], in [kMinLogStd, kMaxLogStd]
};

class ActionDecoderImpl : public torch::nn::Module {
 public:
  static constexpr double kMinLogStd = -5.0, kMaxLogStd = 2.0;

  ActionDecoderImpl(int64_t state_dim, int64_t latent_dim, int64_t action_dim,
                    const std::vector<int>& hidden, bool state_dependent_std = true);

  // state [..., D], z [..., Z] (same leading shape) -> the Gaussian over a.
  ActionDistribution forward(const torch::Tensor& state, const torch::Tensor& z);
  // The mean action [..., A]: the deterministic policy for rollouts and the base of the
  // GAIL residual policy.
  torch::Tensor mean(const torch::Tensor& state, const torch::Tensor& z);
  // log pi(a | x, z) summed over the A components: [...].
  torch::Tensor log_prob(const torch::Tensor& state, const torch::Tensor& z,
                         const torch::Tensor& action);

 private:
  torch::Tensor trunk(const torch::Tensor& state, const torch::Tensor& z);
  torch::nn::ModuleList hidden_;
  torch::nn::Linear mean_{nullptr}, log_std_{nullptr};  // log_std_: state-dependent std only
  torch::Tensor shared_log_std_;                        // [A]: otherwise
};
TORCH_MODULE(ActionDecoder);

}  // namespace vaegail::vae
