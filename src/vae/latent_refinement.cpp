#include "vae/latent_refinement.h"

#include <fmt/format.h>
#include <stdexcept>
#include <string>

namespace vaegail::vae {

namespace {

torch::Device model_device(TrajectoryVae& model) { return model->parameters().front().device(); }

void check_shapes(const TrajectoryVae& model, const TrajectoryDataset& data, const torch::Tensor& z) {
  const int64_t M = data.size(), Z = model->config().latent_dim;
  if (M == 0) throw std::invalid_argument("refine_latents: no demonstrations");
  if (z.dim() != 2 || z.size(0) != M || z.size(1) != Z)
    throw std::invalid_argument("refine_latents: z must be [" + std::to_string(M) + ", " + std::to_string(Z) + "]");
}

torch::Tensor objective_on_device(TrajectoryVae& model, const TrajectoryDataset& data, const torch::Tensor& z) {
  const auto nll = model->decoder_nll(data.states, data.actions, z, data.mask);
  return nll.action + nll.state + 0.5 * z.square().sum(-1);
}

}  // namespace

torch::Tensor latent_objective(TrajectoryVae& model, const TrajectoryDataset& data, const torch::Tensor& z) {
  check_shapes(model, data, z);
  torch::NoGradGuard no_grad;
  const auto device = model_device(model);
  const auto rows = torch::arange(data.size());
  return objective_on_device(model, data.select(rows, device), z.to(device, torch::kFloat)).cpu();
}

torch::Tensor refine_latents(TrajectoryVae& model, const TrajectoryDataset& data, const torch::Tensor& start,
                             const RefineOptions& options, Progress* progress) {
  check_shapes(model, data, start);
  if (options.steps < 0 || options.batch < 1 || !(options.learning_rate > 0))
    throw std::invalid_argument("refine_latents: steps must be >= 0, batch >= 1 and the learning rate > 0");
  torch::AutoGradMode grad_on(true);  // callers evaluate under NoGradGuard
  const auto device = model_device(model);
  std::vector<torch::Tensor> refined;
  for (int64_t b = 0; b < data.size(); b += options.batch) {
    const int64_t n = std::min(options.batch, data.size() - b);
    const auto batch = data.select(torch::arange(b, b + n), device);
    auto z = start.narrow(0, b, n).to(device, torch::kFloat).clone().requires_grad_(true);
    torch::optim::Adam adam({z}, torch::optim::AdamOptions(options.learning_rate));
    for (int step = 0; step < options.steps; ++step) {
      // Only z's gradient: the decoders' parameters stay as trained and gather nothing.
      z.mutable_grad() = torch::autograd::grad({objective_on_device(model, batch, z).sum()}, {z})[0];
      adam.step();
    }
    refined.push_back(z.detach().cpu());
    if (progress) progress->advance(n);
  }
  return torch::cat(refined);
}

RefinedLatents refine_with_report(TrajectoryVae& model, const TrajectoryDataset& data, const torch::Tensor& start,
                                  const RefineOptions& options) {
  RefinedLatents r;
  r.objective_before = latent_objective(model, data, start).mean().item<double>();
  Progress progress("refine z", data.size(), "demos");
  r.z = refine_latents(model, data, start, options, &progress);
  progress.finish();
  r.objective_after = latent_objective(model, data, r.z).mean().item<double>();
  r.description = fmt::format(
      "the encoder's mean refined by {} Adam steps (lr {:g}) towards the mode of p(z | demonstration); "
      "-log p(demonstration, z) per demonstration {:.1f} at the encoder's mean, {:.1f} refined",
      options.steps, options.learning_rate, r.objective_before, r.objective_after);
  return r;
}

}  // namespace vaegail::vae
