#include "vae/demo_dataset.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "util/rng.h"

namespace vaegail::vae {

namespace {

void require_dims(const DemoSet& demos, const VaeConfig& config) {
  const auto& h = demos.header;
  if (h.obs_dim() != config.state_dim || h.act_dim() != config.action_dim)
    throw std::invalid_argument(demos.path + ": observations/actions have " +
                                std::to_string(h.obs_dim()) + "/" + std::to_string(h.act_dim()) +
                                " components but the VAE config '" + config.name + "' expects " +
                                std::to_string(config.state_dim) + "/" +
                                std::to_string(config.action_dim));
}

}  // namespace

TrajectoryDataset to_trajectory_dataset(const DemoSet& demos, const std::vector<int64_t>& episodes,
                                        const VaeConfig& config) {
  require_dims(demos, config);
  const int64_t M = static_cast<int64_t>(episodes.size());
  const int64_t D = config.state_dim, A = config.action_dim;
  int64_t T = 0;
  bool ragged = false;
  for (int64_t i : episodes) {
    const int64_t len = demos.episodes.at(i).length();
    ragged = ragged || (T != 0 && len != T);
    T = std::max(T, len);
  }
  auto states = torch::zeros({M, T + 1, D});
  auto actions = torch::zeros({M, T, A});
  auto mask = torch::zeros({M, T}, torch::kBool);
  for (int64_t m = 0; m < M; ++m) {
    const Episode& e = demos.episodes[episodes[m]];
    const int64_t len = e.length();
    std::copy(e.observations.begin(), e.observations.end(), states[m].data_ptr<float>());
    std::copy(e.actions.begin(), e.actions.end(), actions[m].data_ptr<float>());
    mask[m].narrow(0, 0, len).fill_(true);
  }
  return {states, actions, ragged ? mask : torch::Tensor()};
}

bool is_held_out(const Episode& episode) {
  const auto it = episode.attributes.find("held_out");
  return it != episode.attributes.end() && it->second != 0.0;
}

DemoSplit split_demos(const DemoSet& demos, std::uint64_t seed, double val_fraction) {
  DemoSplit split;
  const int64_t M = static_cast<int64_t>(demos.episodes.size());
  for (int64_t i = 0; i < M; ++i)
    (is_held_out(demos.episodes[i]) ? split.val : split.train).push_back(i);
  if (!split.val.empty() || M < 2) return split;

  std::vector<int64_t> order = split.train;
  Rng rng(seed);
  for (int64_t i = M - 1; i > 0; --i)
    std::swap(order[i], order[rng.next() % static_cast<std::uint64_t>(i + 1)]);
  const int64_t n_val = std::max<int64_t>(1, static_cast<int64_t>(val_fraction * M + 0.5));
  split.val.assign(order.begin(), order.begin() + n_val);
  split.train.assign(order.begin() + n_val, order.end());
  std::sort(split.val.begin(), split.val.end());
  std::sort(split.train.begin(), split.train.end());
  return split;
}

DemoTrainingData make_demo_training_data(DemoSet demos, const VaeConfig& config,
                                         std::uint64_t split_seed) {
  DemoTrainingData d;
  d.demos = std::move(demos);
  require_dims(d.demos, config);
  d.split = split_demos(d.demos, split_seed);
  if (d.split.train.empty())
    throw std::invalid_argument(d.demos.path + ": no training episodes (every episode is held out)");
  d.train = to_trajectory_dataset(d.demos, d.split.train, config);
  if (!d.split.val.empty()) d.val = to_trajectory_dataset(d.demos, d.split.val, config);
  return d;
}

double achieved_speed(const DemoSet& demos, int64_t episode) {
  const Episode& e = demos.episodes.at(episode);
  const auto it = e.attributes.find("mean_com_speed");
  if (it != e.attributes.end()) return it->second;
  const auto& names = demos.header.feature_names;
  const auto f = std::find(names.begin(), names.end(), "com_speed");
  if (f == names.end())
    throw DataError(demos.path + ": episode_" + std::to_string(episode) +
                    ": neither attribute mean_com_speed nor feature com_speed");
  return e.mean_feature(static_cast<int>(f - names.begin()), static_cast<int>(names.size()));
}

double achieved_speed_or_nan(const DemoSet& demos, int64_t episode) {
  try {
    return achieved_speed(demos, episode);
  } catch (const DataError&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

}  // namespace vaegail::vae
