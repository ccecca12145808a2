#include "vae/trained_vae.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "util/checkpoint_file.h"

namespace vaegail::vae {

TrajectoryVae load_trained_vae(const std::string& run, const torch::Device& device) {
  TrajectoryVae model{nullptr};
  read_checkpoint(model_file(run), [&](const std::string& path) {
    torch::serialize::InputArchive archive, model_archive;
    archive.load_from(path, device);
    c10::IValue kind, config_json;
    if (archive.try_read("kind", kind) && kind.toStringRef() != "vae")
      throw std::runtime_error(path + ": the weights of a " + kind.toStringRef() + " run, not of a VAE");
    archive.read("config", config_json);
    model = TrajectoryVae(VaeConfig::from_json(config_json.toStringRef()));
    archive.read("model", model_archive);
    model->load(model_archive);
  });
  model->to(device);
  return model;
}

void save_vae_weights(const TrajectoryVae& model, const std::string& path, int epochs) {
  write_checkpoint(path, [&](std::ostream& out) {
    torch::serialize::OutputArchive archive, model_archive;
    model->save(model_archive);
    archive.write("kind", c10::IValue("vae"));
    archive.write("config", c10::IValue(model->config().to_json()));
    archive.write("model", model_archive);
    if (epochs >= 0) archive.write("epoch", c10::IValue(static_cast<int64_t>(epochs)));
    archive.save_to(out);
  });
}

std::pair<torch::Tensor, torch::Tensor> encode(TrajectoryVae& model, const torch::Tensor& states,
                                               const torch::Tensor& step_mask, int64_t batch_size) {
  torch::NoGradGuard no_grad;
  const auto device = model->state_decoder()->parameters().front().device();
  std::vector<torch::Tensor> mus, sigmas;
  const int64_t M = states.size(0), bs = std::max<int64_t>(1, batch_size);
  for (int64_t b = 0; b < M; b += bs) {
    const int64_t n = std::min(bs, M - b);
    const auto s = states.narrow(0, b, n).to(device);
    const auto m = step_mask.defined()
                       ? state_mask_from_step_mask(step_mask.narrow(0, b, n).to(device))
                       : torch::Tensor();
    const auto q = model->encode(s, m);
    mus.push_back(q.mean.cpu());
    sigmas.push_back(q.log_std.exp().cpu());
  }
  return {torch::cat(mus), torch::cat(sigmas)};
}

LatentPolicy vae_mean_policy(TrajectoryVae model, torch::Device device) {
  return [model, device](const torch::Tensor& obs, const torch::Tensor& z) mutable {
    return model->action_mean(obs.to(device), z.to(device));
  };
}

}  // namespace vaegail::vae
