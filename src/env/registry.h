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
  // MJCF bodies only (GenericTaskEnv):
  int frame_skip = 0;            // physics steps per control step; 0: the MJCF's own, else 1
  std::string mjcf_text;         // the body's MJCF (a demonstration file's): compiled from this
                                 // text, `task` naming it, instead of reading the file at `task`
  std::vector<std::string> context_names;  // beyond the MJCF's own
  double control_timestep = 0;   // > 0 with frame_skip 0: the frame skip that gives this step
};

std::vector<std::string> builtin_tasks();
// Throws std::invalid_argument naming the task when it is neither built in nor an MJCF path.
// An MJCF path (or text) gets the default task of generic_task.h.
std::unique_ptr<Env> make_env(const EnvRequest& request);

}  // namespace vaegail
