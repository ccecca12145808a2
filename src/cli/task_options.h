// Flags shared by the commands that build an environment.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

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

}  // namespace vaegail::cli
