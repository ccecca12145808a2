#include "gail/gail_demos.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "vae/demo_dataset.h"
#include "vae/vae_trainer.h"

namespace vaegail {

namespace {

torch::Tensor step_rows(const std::vector<float>& values, int rows, int dim) {
  return torch::from_blob(const_cast<float*>(values.data()), {rows, dim}, torch::kFloat32).clone();
}

}  // namespace

std::vector<float> GailDemos::sample_latent(int m, Rng& rng) const {
  std::vector<float> z(latent_dim());
  const auto mu_m = mu[m].contiguous(), sigma_m = sigma[m].contiguous();
  for (size_t k = 0; k < z.size(); ++k)
    z[k] = mu_m.data_ptr<float>()[k] + sigma_m.data_ptr<float>()[k] * static_cast<float>(rng.normal());
  return z;
}

std::pair<torch::Tensor, torch::Tensor> GailDemos::sample_steps(const torch::Tensor& episode,
                                                                torch::Generator& generator,
                                                                const RowSlice& slice) const {
  const auto e = episode.to(torch::kCPU, torch::kLong);
  const auto u = slice.global_rows.defined()
                     ? torch::rand({slice.global_size}, generator, torch::kFloat64).index_select(0, slice.global_rows)
                     : torch::rand({e.size(0)}, generator, torch::kFloat64);
  const auto step = (u * lengths.index_select(0, e).to(torch::kFloat64)).to(torch::kLong);
  const auto rows = offsets.index_select(0, e) + step;
  return {observations.index_select(0, rows), actions.index_select(0, rows)};
}

GailDemos make_gail_demos(const DemoSet& demos, const std::vector<int64_t>& episodes, vae::TrajectoryVae* vae) {
  if (episodes.empty()) throw std::invalid_argument(demos.path + ": no training episodes");
  const int obs_dim = demos.header.obs_dim(), act_dim = demos.header.act_dim();
  GailDemos out;
  out.episodes = episodes;
  std::vector<torch::Tensor> obs, act;
  std::vector<int64_t> offsets, lengths;
  int64_t offset = 0;
  for (int64_t i : episodes) {
    const Episode& e = demos.episodes.at(i);
    const int T = e.length();
    obs.push_back(step_rows(e.observations, T + 1, obs_dim).slice(0, 0, T));
    act.push_back(step_rows(e.actions, T, act_dim));
    offsets.push_back(offset);
    lengths.push_back(T);
    offset += T;
    out.contexts.push_back(e.context);
    out.achieved_speeds.push_back(vae::achieved_speed_or_nan(demos, i));
  }
  out.observations = torch::cat(obs);
  out.actions = torch::cat(act);
  out.offsets = torch::tensor(offsets, torch::kLong);
  out.lengths = torch::tensor(lengths, torch::kLong);
  if (vae) {
    torch::NoGradGuard no_grad;
    const auto data = vae::to_trajectory_dataset(demos, episodes, (*vae)->config());
    std::tie(out.mu, out.sigma) = vae::encode(*vae, data);
    out.mu = out.mu.to(torch::kFloat32).contiguous();
    out.sigma = out.sigma.to(torch::kFloat32).contiguous();
  } else {
    out.mu = out.sigma = torch::zeros({out.size(), 0});
  }
  return out;
}

}  // namespace vaegail
