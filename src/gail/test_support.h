// Shared by the gail tests: a tiny VAE and one-thread Torch.
#pragma once

#include <gtest/gtest.h>
#include <torch/torch.h>

#include "vae/trajectory_vae.h"
#include "vae/vae_config.h"

namespace vaegail {

class SingleThreadTorch : public ::testing::Environment {
 public:
  void SetUp() override { torch::set_num_threads(1); }
};
inline ::testing::Environment* const kSingleThreadTorch = ::testing::AddGlobalTestEnvironment(new SingleThreadTorch);

// The walker preset shrunk to test size (untrained: the GAIL stage only needs its shapes,
// its encoder and its action mean).
inline vae::VaeConfig tiny_vae_config(int state_dim, int action_dim, int latent_dim = 2) {
  vae::VaeConfig c = vae::VaeConfig::walker(state_dim, action_dim);
  c.lstm_hidden = 8;
  c.latent_dim = latent_dim;
  c.action_hidden = {16};
  c.wavenet_channels = 4;
  c.wavenet_layers = 1;
  c.mixture_components = 1;
  return c;
}

}  // namespace vaegail
