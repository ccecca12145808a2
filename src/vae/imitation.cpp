#include "vae/imitation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "data/record.h"
#include "util/progress.h"
#include "util/rng.h"
#include "vae/vae_trainer.h"
#include "vae/demo_dataset.h"

namespace vaegail::vae {

namespace {

int feature_index(const Env& env, const std::string& name) {
  const auto& names = env.feature_names();
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

// The first step whose state had fallen, or the terminating step; -1 when neither.
int fall_step(const Episode& e, int fallen_feature, int n_features) {
  if (fallen_feature >= 0)
    for (size_t r = 0; r * n_features < e.features.size(); ++r)
      if (e.features[r * n_features + fallen_feature] > 0.5) return static_cast<int>(r);
  if (!e.terminations.empty() && e.terminations.back()) return e.length();
  return -1;
}

}  // namespace

std::vector<RolloutStart> rollout_starts(const DemoSet& demos, const std::vector<int64_t>& episodes) {
  std::vector<RolloutStart> starts;
  for (int64_t i : episodes) starts.push_back({demos.episodes.at(i).seed, demos.episodes.at(i).context});
  return starts;
}

std::vector<ImitationOutcome> roll_out_latent_policy(const Env& prototype,
                                                     const std::vector<RolloutStart>& starts,
                                                     const torch::Tensor& z,
                                                     const LatentPolicy& policy,
                                                     const ImitationOptions& options,
                                                     Progress* progress) {
  const int64_t M = static_cast<int64_t>(starts.size());
  if (z.dim() != 2 || z.size(0) != M)
    throw std::invalid_argument("roll_out_latent_policy: z must be [" + std::to_string(M) + ", Z]");
  const auto z_cpu = z.detach().to(torch::kCPU, torch::kFloat).contiguous();
  const LatentSchedule fixed = [&z_cpu](const torch::Tensor& rows, const torch::Tensor&) {
    return z_cpu.index_select(0, rows);
  };
  return roll_out_latent_policy(prototype, starts, fixed, policy, options, progress);
}

std::vector<ImitationOutcome> roll_out_latent_policy(const Env& prototype,
                                                     const std::vector<RolloutStart>& starts,
                                                     const LatentSchedule& z,
                                                     const LatentPolicy& policy,
                                                     const ImitationOptions& options,
                                                     Progress* progress) {
  const int speed = options.speed_feature.empty() ? -1 : feature_index(prototype, options.speed_feature);
  if (speed < 0 && !options.speed_feature.empty())
    throw std::invalid_argument("roll_out_latent_policy: env '" + prototype.id() +
                                "' has no feature '" + options.speed_feature + "'");
  const int obs_dim = prototype.obs_dim(), act_dim = prototype.act_dim();

  RecordRequest request;
  for (const auto& s : starts) {
    request.seeds.push_back(options.start_seed ? derive_seed(s.seed, options.start_seed) : s.seed);
    request.contexts.push_back(s.context.empty() ? prototype.context() : s.context);
  }
  request.num_envs = options.num_envs;
  request.num_threads = options.num_threads;
  const BatchPolicy batch = [&](int n, const float* observations, const int* episodes, const int* steps,
                                float* actions) {
    torch::NoGradGuard no_grad;
    const auto obs = torch::from_blob(const_cast<float*>(observations), {n, obs_dim});
    const auto rows = torch::from_blob(const_cast<int*>(episodes), {n}, torch::kInt).to(torch::kLong);
    const auto taken = torch::from_blob(const_cast<int*>(steps), {n}, torch::kInt).to(torch::kLong);
    const auto a = policy(obs, z(rows, taken)).to(torch::kCPU, torch::kFloat).contiguous();
    if (a.dim() != 2 || a.size(0) != n || a.size(1) != act_dim)
      throw std::invalid_argument("roll_out_latent_policy: the policy must return [N, " +
                                  std::to_string(act_dim) + "] actions");
    std::copy(a.data_ptr<float>(), a.data_ptr<float>() + n * act_dim, actions);
  };
  auto episodes = record_episodes(prototype, request, batch, progress);

  const int n_features = static_cast<int>(prototype.feature_names().size());
  const int fallen = feature_index(prototype, options.fallen_feature);
  std::vector<ImitationOutcome> out;
  for (auto& e : episodes) {
    ImitationOutcome o;
    if (speed >= 0) o.achieved_speed = e.mean_feature(speed, n_features);
    o.fall_step = fall_step(e, fallen, n_features);
    o.fell = o.fall_step >= 0;
    o.episode = std::move(e);
    out.push_back(std::move(o));
  }
  return out;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double median_abs_difference(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) throw std::invalid_argument("median_abs_difference: sizes differ");
  std::vector<double> d;
  for (size_t i = 0; i < a.size(); ++i) d.push_back(std::abs(a[i] - b[i]));
  return median(std::move(d));
}

torch::Tensor encode_episodes(TrajectoryVae& model, const DemoSet& demos, const std::vector<int64_t>& episodes,
                              torch::Tensor* sigma, Progress* progress) {
  torch::NoGradGuard no_grad;
  const auto data = to_trajectory_dataset(demos, episodes, model->config());
  const int64_t M = data.size(), batch = 64;
  std::vector<torch::Tensor> mus, sigmas;
  for (int64_t b = 0; b < M; b += batch) {
    const int64_t n = std::min(batch, M - b);
    const auto [mu, s] = encode(model, data.states.narrow(0, b, n),
                                data.mask.defined() ? data.mask.narrow(0, b, n) : torch::Tensor(), n);
    mus.push_back(mu);
    sigmas.push_back(s);
    if (progress) progress->advance(n);
  }
  if (sigma) *sigma = torch::cat(sigmas);
  return torch::cat(mus);
}

}  // namespace vaegail::vae
