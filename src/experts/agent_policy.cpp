#include "experts/agent_policy.h"

#include "util/rng.h"

namespace vaegail {

BatchPolicy agent_batch_policy(std::shared_ptr<Agent> agent, std::vector<std::vector<float>> conditions,
                               bool stochastic, std::uint64_t seed) {
  auto noise = std::make_shared<EpisodeStreams>(seed);
  return [agent, conditions = std::move(conditions), stochastic, noise](
             int n, const float* observations, const int* episodes, const int*, float* actions) {
    torch::NoGradGuard no_grad;
    const int obs_dim = agent->obs_dim(), cond_dim = agent->condition_dim(), act_dim = agent->act_dim();
    torch::Tensor obs = torch::from_blob(const_cast<float*>(observations), {n, obs_dim}).clone();
    torch::Tensor cond = torch::zeros({n, cond_dim});
    for (int b = 0; b < n; ++b)
      for (int k = 0; k < cond_dim; ++k) cond[b][k] = conditions.at(episodes[b]).at(k);
    const DiagGaussian dist = agent->policy().distribution(agent->input(obs, cond));
    torch::Tensor mean = dist.mean.to(torch::kCPU).contiguous();
    torch::Tensor std = dist.log_std.exp().expand_as(dist.mean).to(torch::kCPU).contiguous();
    const float* m = mean.data_ptr<float>();
    const float* s = std.data_ptr<float>();
    for (int b = 0; b < n; ++b) {
      Rng* rng = stochastic ? &(*noise)(episodes[b]) : nullptr;
      for (int a = 0; a < act_dim; ++a) {
        const int i = b * act_dim + a;
        actions[i] = rng ? static_cast<float>(m[i] + s[i] * rng->normal()) : m[i];
      }
    }
  };
}

}  // namespace vaegail
