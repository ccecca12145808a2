#include "vae/trajectory_encoder.h"

#include <stdexcept>

namespace vaegail::vae {

torch::Tensor mask_lengths(const torch::Tensor& mask) {
  const auto m = mask.to(torch::kCPU).to(torch::kBool);
  if (m.dim() != 2) throw std::invalid_argument("mask must be [B, steps]");
  const auto lengths = m.sum(1).to(torch::kLong);
  const auto prefix = torch::arange(m.size(1)).unsqueeze(0) < lengths.unsqueeze(1);
  if (!torch::equal(prefix, m))
    throw std::invalid_argument("mask: the real steps of each row must be a prefix");
  if (m.size(0) > 0 && lengths.min().item<int64_t>() < 1)
    throw std::invalid_argument("mask: every row needs at least one real step");
  return lengths;
}

TrajectoryEncoderImpl::TrajectoryEncoderImpl(int64_t state_dim, int64_t hidden,
                                             int64_t latent_dim) {
  lstm_ = register_module("lstm", BiLstm(state_dim, hidden, /*layers=*/2));
  head_ = register_module("head", torch::nn::Linear(2 * hidden, 2 * latent_dim));
}

torch::Tensor TrajectoryEncoderImpl::pooled_features(const torch::Tensor& states,
                                                     const torch::Tensor& mask) {
  TORCH_CHECK(states.dim() == 3, "TrajectoryEncoder: states must be [B, S, D]");
  const int64_t B = states.size(0), S = states.size(1);
  if (mask.defined())
    TORCH_CHECK(mask.sizes() == states.sizes().slice(0, 2), "TrajectoryEncoder: mask must be [B, S]");
  const auto lengths = mask.defined() ? mask_lengths(mask) : torch::full({B}, S, torch::kLong);
  // Padded outputs are zeros, so the sum over time counts real steps only.
  const auto out = lstm_(states, lengths);
  return out.sum(1) / lengths.to(out.device(), out.scalar_type()).unsqueeze(1);
}

EncoderOutput TrajectoryEncoderImpl::forward(const torch::Tensor& states,
                                             const torch::Tensor& mask) {
  const auto out = head_(pooled_features(states, mask));
  const auto parts = out.chunk(2, -1);
  return {parts[0], parts[1]};
}

}  // namespace vaegail::vae
