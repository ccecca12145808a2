#include "vae/action_error.h"

#include <cmath>
#include <stdexcept>

namespace vaegail::vae {

namespace {

double rms_over(const torch::Tensor& squared, const torch::Tensor& weight) {
  const double n = weight.sum().item<double>();
  return n > 0 ? std::sqrt((squared * weight).sum().item<double>() / n) : 0.0;
}

}  // namespace

ActionError teacher_forced_action_error(TrajectoryVae& model, const TrajectoryDataset& data,
                                        const torch::Tensor& z) {
  torch::NoGradGuard no_grad;
  const int64_t M = data.size();
  if (M == 0) throw std::invalid_argument("teacher_forced_action_error: no demonstrations");
  if (z.dim() != 2 || z.size(0) != M)
    throw std::invalid_argument("teacher_forced_action_error: z must be [" + std::to_string(M) + ", Z]");
  const auto device = model->state_decoder()->parameters().front().device();
  const int64_t T = data.actions.size(1);
  const auto states = data.states.narrow(1, 0, T).to(device);
  const auto actions = data.actions.to(device);
  const auto z_steps = z.to(device, states.scalar_type()).unsqueeze(1).expand({M, T, z.size(1)});
  auto squared = (model->action_mean(states, z_steps) - actions).square().mean(-1);  // [M, T]
  auto real = data.mask.defined() ? data.mask.to(device, squared.scalar_type())
                                  : torch::ones_like(squared);
  squared = torch::where(real > 0, squared, torch::zeros_like(squared));  // NaN padding
  auto first = torch::zeros_like(real);
  first.select(1, 0).fill_(1.0);
  return {rms_over(squared, real * first), rms_over(squared, real * (1 - first))};
}

std::vector<ActionErrorRow> action_error_by_z_source(TrajectoryVae& model,
                                                     const TrajectoryDataset& data,
                                                     const torch::Tensor& mu) {
  return {{"own", teacher_forced_action_error(model, data, mu)},
          {"another episode's", teacher_forced_action_error(model, data, mu.roll(mu.size(0) / 2, 0))},
          {"zero", teacher_forced_action_error(model, data, torch::zeros_like(mu))}};
}

}  // namespace vaegail::vae
