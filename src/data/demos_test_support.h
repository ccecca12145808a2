// Shared by the demonstration-file tests: a two-episode toy file and its expected contents.
#pragma once

#include <filesystem>
#include <string>

#include "data/demos.h"

namespace vaegail {

inline DemoHeader toy_header() {
  DemoHeader h;
  h.env_id = "toy";
  h.control_timestep = 0.025;
  h.observation_names = {"x", "v"};
  h.action_names = {"f"};
  h.feature_names = {"speed"};
  h.context_names = {"target_speed"};
  return h;
}

// src/data/testdata/write_h5py_demos.py writes the same values: keep the two in step.
inline Episode toy_episode(int T, float offset) {
  Episode e;
  for (int t = 0; t <= T; ++t) {
    e.observations.push_back(offset + t);
    e.observations.push_back(-offset * t);
    e.features.push_back(0.1 * t + offset);
  }
  for (int t = 0; t < T; ++t) {
    e.actions.push_back(0.5f * t);
    e.rewards.push_back(1.0 / (t + 1));
    e.terminations.push_back(t == T - 1 && offset > 1);
    e.truncations.push_back(t == T - 1 && offset <= 1);
  }
  e.expert_id = "expert_" + std::to_string(static_cast<int>(offset));
  e.context = {offset};
  e.seed = 0xFFFFFFFFFFFFFFF1ULL;  // beyond double precision: must survive exactly
  e.attributes["achieved_speed"] = offset * 0.5;
  return e;
}

// The toy file's episodes: 5 steps at offset 1, 3 steps at offset 2.
inline Episode toy_file_episode(int index) { return index == 0 ? toy_episode(5, 1) : toy_episode(3, 2); }

// "" when `set` holds exactly the toy file's header and episodes, else the first field that
// differs ("episode_1/actions").
inline std::string toy_contents_difference(const DemoSet& set) {
  const DemoHeader h = toy_header();
  if (set.header.env_id != h.env_id || set.header.control_timestep != h.control_timestep ||
      set.header.observation_names != h.observation_names || set.header.action_names != h.action_names ||
      set.header.feature_names != h.feature_names || set.header.context_names != h.context_names)
    return "header";
  if (set.episodes.size() != 2) return "episode count " + std::to_string(set.episodes.size());
  for (int i = 0; i < 2; ++i) {
    const Episode expected = toy_file_episode(i);
    const Episode& got = set.episodes[i];
    const std::string name = "episode_" + std::to_string(i) + "/";
    if (got.observations != expected.observations) return name + "observations";
    if (got.actions != expected.actions) return name + "actions";
    if (got.rewards != expected.rewards) return name + "rewards";
    if (got.terminations != expected.terminations) return name + "terminations";
    if (got.truncations != expected.truncations) return name + "truncations";
    if (got.features != expected.features) return name + "features";
    if (got.expert_id != expected.expert_id) return name + "expert_id";
    if (got.context != expected.context) return name + "context";
    if (got.seed != expected.seed) return name + "seed";
    if (got.attributes != expected.attributes) return name + "attributes";
  }
  return "";
}

inline std::string temp_demo_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("vaegail_demos_" + name + ".h5")).string();
}

inline void write_toy_file_at(const std::string& path) {
  DemoWriter w(path, toy_header());
  for (int i = 0; i < 2; ++i) w.append(toy_file_episode(i));
  w.commit();
}

inline std::string write_toy_file(const std::string& name) {
  const std::string path = temp_demo_path(name);
  write_toy_file_at(path);
  return path;
}

}  // namespace vaegail
