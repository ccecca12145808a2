// Flags shared by the commands that build an environment.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include <torch/torch.h>

#include "data/demos.h"
#include "env/registry.h"

namespace vaegail::cli {

struct TaskOptions {
  std::string task = "walker";
  int episode_length = 0;
  int frame_skip = 1;
  bool keep_going_after_fall = false;

  EnvRequest request() const;
  std::unique_ptr<Env> make() const { return make_env(request()); }
};

// "cpu" or "cuda"; throws (one line) if CUDA is asked for and this LibTorch has none.
torch::Device parse_device(const std::string& name);

// The environment the demonstrations were recorded in, with episodes as long as the longest.
EnvRequest demo_env_request(const DemoSet& demos);
inline std::unique_ptr<Env> demo_env(const DemoSet& demos) { return make_env(demo_env_request(demos)); }

}  // namespace vaegail::cli
