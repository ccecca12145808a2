#include "vae/trajectory_encoder.h"

#include <stdexcept>

namespace vaegail::vae {

namespace rnn = torch::nn::utils::rnn;

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
  lstm_ = register_module("lstm", torch::nn::LSTM(torch::nn::LSTMOptions(state_dim, hidden)
                                                      .num_layers(2)
                                                      .bidirectional(true)
                                                      .batch_first(true)));
  head_ = register_module("head", torch::nn::Linear(2 * hidden, 2 * latent_dim));
}

torch::Tensor TrajectoryEncoderImpl::pooled_features(const torch::Tensor& states,
                                                     const torch::Tensor& mask) {
  TORCH_CHECK(states.dim() == 3, "TrajectoryEncoder: states must be [B, S, D]");
  const int64_t S = states.size(1);
  if (!mask.defined() || mask.to(torch::kBool).all().item<bool>()) {
    if (mask.defined()) TORCH_CHECK(mask.sizes() == states.sizes().slice(0, 2), "mask shape");
    return std::get<0>(lstm_->forward(states)).mean(1);
  }
  TORCH_CHECK(mask.sizes() == states.sizes().slice(0, 2), "TrajectoryEncoder: mask must be [B, S]");
  const auto lengths = mask_lengths(mask);
  const auto packed = rnn::pack_padded_sequence(states, lengths, /*batch_first=*/true,
                                                /*enforce_sorted=*/false);
  const auto out = std::get<0>(lstm_->forward_with_packed_input(packed));
  // Padded outputs are zeros, so the sum over time counts real steps only.
  const auto padded = std::get<0>(rnn::pad_packed_sequence(out, /*batch_first=*/true,
                                                           /*padding_value=*/0.0, S));
  return padded.sum(1) / lengths.to(padded.device(), padded.scalar_type()).unsqueeze(1);
}

EncoderOutput TrajectoryEncoderImpl::forward(const torch::Tensor& states,
                                             const torch::Tensor& mask) {
  const auto out = head_(pooled_features(states, mask));
  const auto parts = out.chunk(2, -1);
  return {parts[0], parts[1]};
}

}  // namespace vaegail::vae
