// State decoder p_w(x_{t+1} | x_t, z): a conditional WaveNet that is autoregressive over the
// D components of x_{t+1} (paper section 3.1, Figure 1 right), with a mixture of K Gaussians
// per component as its output instead of WaveNet's softmax.
//
// For one position (a time step t of one trajectory) the sequence axis is the component
// index k = 0..D-1 and there is 1 input channel: u_k = x_{t+1}[k-1], u_0 = 0 (the target
// shifted right by one). Then
//   h_0     = u w_in + b_in                                    (1x1, 1 -> C channels)
//   layer l = 0..L-1, dilation d_l:
//     a     = W_l [h(k) ; h(k - d_l)] + V_l c + P_l[k]          (causal conv, kernel 2)
//     g     = tanh(a_filter) * sigmoid(a_gate)                 (gated activation)
//     h    += R_l g + b_res,   skip += S_l g + b_skip             (residual and skip)
//   head    = 1x1(ReLU(1x1(ReLU(skip))))  -> K logits, K means, K log-stds per component
// where c = (x_t, z) is the global conditioning, projected once per position and broadcast
// over the D components, and h(k - d) = 0 for k < d.
//
// Dilations are 1, 2, 4, ... and wrap modulo ceil(log2 D): with more layers than that, a
// dilation >= D would only ever read the zero padding, so the sequence restarts at 1 (walker:
// D = 18, L = 6 -> 1 2 4 8 16 1). The receptive field 1 + sum(d_l) covers all D components
// once L >= ceil(log2 D) (any k < D sees u_0..u_k, i.e. x_{t+1}[0..k-1]).
//
// Position: P_l[k] is a learned per-component bias of each gated layer (it replaces the
// convolution's bias). A WaveNet with only global conditioning applies the same function
// at every k and could tell components apart only through the zero padding at the start;
// state components have unrelated meanings and scales, so each needs its own offset. With
// config.position_embedding = false P_l is one bias shared by all k (plain WaveNet).
//
// Causality is exact: the distribution of component k depends on x_{t+1}[0..k-1] only.
//
// On the CPU (float32) forward() runs the fused kernel of state_decoder_kernel.h; on any
// other device, or via forward_reference(), a plain conv1d implementation of the same model.
#pragma once

#include <torch/torch.h>

#include <vector>

#include "vae/mixture.h"
#include "vae/state_decoder_kernel.h"

namespace vaegail::vae {

struct StateDecoderOptions {
  int64_t state_dim = 18;  // D
  int64_t cond_dim = 38;   // size of c = (x_t, z): D + latent
  int64_t channels = 32;   // C
  int64_t layers = 6;      // L
  int64_t components = 5;  // K
  bool position_embedding = true;
};

// 1, 2, 4, ... wrapping modulo ceil(log2 D) (see above); all 1 when D <= 2.
std::vector<int64_t> wavenet_dilations(int64_t layers, int64_t state_dim);

class StateDecoderImpl : public torch::nn::Module {
 public:
  explicit StateDecoderImpl(const StateDecoderOptions& options);

  // prev = x_t [N, D], next = x_{t+1} [N, D] (only its components < k are seen at k),
  // z [N, latent] -> the mixture for every component, each tensor [N, D, K].
  MixtureParams forward(const torch::Tensor& prev, const torch::Tensor& next,
                        const torch::Tensor& z);
  // The same model written with torch::conv1d (any device); the kernel's test oracle.
  MixtureParams forward_reference(const torch::Tensor& prev, const torch::Tensor& next,
                                  const torch::Tensor& z);
  // log p_w(x_{t+1}[k] | x_{t+1}[<k], x_t, z) per component: [N, D]. Sum over D for the
  // log-density of the whole vector.
  torch::Tensor log_prob(const torch::Tensor& prev, const torch::Tensor& next,
                         const torch::Tensor& z);
  // Draws x_{t+1} [N, D] component by component (D network passes, no gradient).
  torch::Tensor sample(const torch::Tensor& prev, const torch::Tensor& z,
                       c10::optional<at::Generator> generator = c10::nullopt);

  const StateDecoderOptions& options() const { return options_; }
  const std::vector<int64_t>& dilations() const { return dilations_; }
  WaveNetStackWeights stack_weights() const;
  // Whether forward() takes the fused kernel for inputs like `x`.
  bool uses_kernel(const torch::Tensor& x) const;

 private:
  torch::Tensor shifted_inputs(const torch::Tensor& next) const;  // [N, D], u_0 = 0
  torch::Tensor conditioning(const torch::Tensor& prev, const torch::Tensor& z);  // [N, L, 2C]
  MixtureParams head(const torch::Tensor& skip);  // skip [N, D, C]

  StateDecoderOptions options_;
  std::vector<int64_t> dilations_;
  torch::Tensor in_weight_, in_bias_, gate_weight_, gate_bias_, out_weight_, out_bias_;
  torch::nn::Linear cond_proj_{nullptr}, head_hidden_{nullptr}, head_out_{nullptr};
};
TORCH_MODULE(StateDecoder);

}  // namespace vaegail::vae
