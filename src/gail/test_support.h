// Shared by the gail tests: a tiny VAE, random walker demonstrations and one-thread Torch.
#pragma once

#include <gtest/gtest.h>
#include <torch/torch.h>

#include "data/record.h"
#include "env/env.h"
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

// Walker episodes of random actions, with target speeds -1 and 1 as their contexts.
inline DemoSet random_walker_demos(const Env& env, int episodes) {
  RecordRequest request;
  for (int i = 0; i < episodes; ++i) {
    request.seeds.push_back(100 + i);
    request.contexts.push_back({i % 2 ? 1.0 : -1.0});
  }
  DemoSet demos;
  demos.path = "random.h5";
  demos.header = header_for(env);
  demos.episodes = record_episodes(env, request, random_policy(env, 7));
  return demos;
}

}  // namespace vaegail
