// Encoder q_phi(z | x_{1:T}) (paper section 3.1): a 2-layer bidirectional LSTM over the
// states, the mean over time of ALL second-layer outputs (both directions), then a linear
// map to the mean and log-std of a diagonal Gaussian over z.
#pragma once

#include <torch/torch.h>

#include "vae/bilstm.h"

namespace vaegail::vae {

struct EncoderOutput {
  torch::Tensor mean;     // [B, Z]
  torch::Tensor log_std;  // [B, Z]
};

class TrajectoryEncoderImpl : public torch::nn::Module {
 public:
  TrajectoryEncoderImpl(int64_t state_dim, int64_t hidden, int64_t latent_dim);

  // states [B, S, D]; mask [B, S] (bool or 0/1, true = real step, a prefix of each row) or
  // undefined for all real. Masked steps are neither read by the LSTM (each row runs at its own
  // length, so the backward direction starts at the row's last real step) nor counted in the
  // mean.
  EncoderOutput forward(const torch::Tensor& states, const torch::Tensor& mask = {});
  // The pooled LSTM features [B, 2 * hidden] (the input of the final linear map).
  torch::Tensor pooled_features(const torch::Tensor& states, const torch::Tensor& mask = {});

  BiLstm& lstm() { return lstm_; }

 private:
  BiLstm lstm_{nullptr};  // registered as "lstm", the stock module's name and parameters
  torch::nn::Linear head_{nullptr};
};
TORCH_MODULE(TrajectoryEncoder);

// Row lengths [B] (int64, CPU) of a prefix mask [B, S]; throws std::invalid_argument when a
// row is empty or its real steps are not a prefix.
torch::Tensor mask_lengths(const torch::Tensor& mask);

}  // namespace vaegail::vae
