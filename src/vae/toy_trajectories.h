// Small synthetic trajectory sets for the VAE's tests (header-only, test code only).
#pragma once

#include <torch/torch.h>

#include <cmath>

#include "vae/vae_config.h"

namespace vaegail::vae::testing {

// M trajectories of T steps with D state and A action components. Trajectory m has its own
// frequency and phase ("style"), so trajectories differ; states are smooth in t and actions
// are a fixed function of the state. Returns states [M, T+1, D], actions [M, T, A].
inline std::pair<torch::Tensor, torch::Tensor> toy_trajectories(int64_t M, int64_t T, int64_t D,
                                                                int64_t A, uint64_t seed) {
  auto gen = at::detail::createCPUGenerator(seed);
  const auto opts = torch::TensorOptions(torch::kFloat);
  const auto freq = 0.2 + 0.4 * at::rand({M, 1, 1}, gen, opts);
  const auto phase = 6.28 * at::rand({M, 1, 1}, gen, opts);
  const auto t = torch::arange(T + 1, opts).view({1, T + 1, 1});
  const auto d = torch::arange(D, opts).view({1, 1, D});
  const auto states = torch::sin(freq * t + phase + 0.7 * d) * (1.0 + 0.1 * d);
  const auto w = torch::linspace(-1, 1, D * A, opts).view({D, A});
  const auto actions = torch::tanh(torch::matmul(states.narrow(1, 0, T), w));
  return {states, actions};
}

// A VAE small enough for a unit test: z 2, BiLSTM 16, decoder (32, 32), WaveNet 8 x 2, 2 Gaussians.
inline VaeConfig tiny_vae_config(int64_t D = 4, int64_t A = 2) {
  VaeConfig c = VaeConfig::walker(static_cast<int>(D), static_cast<int>(A));
  c.lstm_hidden = 16;
  c.latent_dim = 2;
  c.action_hidden = {32, 32};
  c.wavenet_channels = 8;
  c.wavenet_layers = 2;
  c.mixture_components = 2;
  return c;
}

}  // namespace vaegail::vae::testing
