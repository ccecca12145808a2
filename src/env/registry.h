// Environments by name: the built-in tasks, or the path of any MJCF file.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "env/env.h"

namespace vaegail {

struct EnvRequest {
  std::string task = "walker";   // a built-in task name, or a path ending in .xml
  int episode_length = 0;        // 0: the task's own default
  bool terminate_on_fall = true; // tasks that can fall end the episode there
  int frame_skip = 1;            // MJCF files only: physics steps per control step
};

std::vector<std::string> builtin_tasks();
// Throws std::invalid_argument naming the task when it is neither built in nor an MJCF path.
std::unique_ptr<Env> make_env(const EnvRequest& request);

}  // namespace vaegail
