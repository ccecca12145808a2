#include "vae/state_decoder.h"

#include <cmath>

#include "vae/gaussian.h"

namespace vaegail::vae {

namespace {
// Bounds of the mixture's log-stds in normalised units: e^-7 ~ 1e-3 std, e^2 ~ 7.4 std.
constexpr double kMinLogStd = -7.0, kMaxLogStd = 2.0;

torch::Tensor uniform(torch::IntArrayRef shape, double fan_in) {
  const double bound = 1.0 / std::sqrt(fan_in);
  return torch::empty(shape).uniform_(-bound, bound);
}
}  // namespace

std::vector<int64_t> wavenet_dilations(int64_t layers, int64_t state_dim) {
  int64_t cycle = 0;  // ceil(log2 D)
  while ((int64_t{1} << cycle) < state_dim) ++cycle;
  std::vector<int64_t> d;
  for (int64_t l = 0; l < layers; ++l) d.push_back(cycle == 0 ? 1 : int64_t{1} << (l % cycle));
  return d;
}

StateDecoderImpl::StateDecoderImpl(const StateDecoderOptions& o)
    : options_(o), dilations_(wavenet_dilations(o.layers, o.state_dim)) {
  TORCH_CHECK(o.state_dim >= 1 && o.cond_dim >= 1 && o.channels >= 1 && o.layers >= 1 &&
                  o.components >= 1,
              "StateDecoder: sizes must be positive");
  const int64_t C = o.channels, L = o.layers, P = o.position_embedding ? o.state_dim : 1;
  in_weight_ = register_parameter("in_weight", uniform({C}, 1.0));
  in_bias_ = register_parameter("in_bias", uniform({C}, 1.0));
  gate_weight_ = register_parameter("gate_weight", uniform({L, 2 * C, 2 * C}, 2.0 * C));
  gate_bias_ = register_parameter("gate_bias", torch::zeros({L, P, 2 * C}));
  out_weight_ = register_parameter("out_weight", uniform({L, 2 * C, C}, C));
  out_bias_ = register_parameter("out_bias", torch::zeros({L, 2 * C}));
  cond_proj_ = register_module(
      "cond_proj", torch::nn::Linear(torch::nn::LinearOptions(o.cond_dim, L * 2 * C).bias(false)));
  head_hidden_ = register_module("head_hidden", torch::nn::Linear(C, C));
  head_out_ = register_module("head_out", torch::nn::Linear(C, 3 * o.components));
}

WaveNetStackWeights StateDecoderImpl::stack_weights() const {
  return {in_weight_, in_bias_, gate_weight_, gate_bias_, out_weight_, out_bias_, dilations_};
}

bool StateDecoderImpl::uses_kernel(const torch::Tensor& x) const {
  return wavenet_kernel_supports(x) && in_weight_.device().is_cpu() &&
         in_weight_.scalar_type() == torch::kFloat;
}

torch::Tensor StateDecoderImpl::shifted_inputs(const torch::Tensor& next) const {
  TORCH_CHECK(next.dim() == 2 && next.size(1) == options_.state_dim,
              "StateDecoder: next state must be [N, ", options_.state_dim, "]");
  return torch::constant_pad_nd(next.narrow(1, 0, options_.state_dim - 1), {1, 0}, 0.0);
}

torch::Tensor StateDecoderImpl::conditioning(const torch::Tensor& prev, const torch::Tensor& z) {
  TORCH_CHECK(prev.dim() == 2 && z.dim() == 2 && prev.size(0) == z.size(0) &&
                  prev.size(1) + z.size(1) == options_.cond_dim,
              "StateDecoder: prev [N, D] and z [N, latent] must give cond_dim columns");
  return cond_proj_(torch::cat({prev, z}, 1))
      .view({prev.size(0), options_.layers, 2 * options_.channels});
}

MixtureParams StateDecoderImpl::head(const torch::Tensor& skip) {
  const int64_t K = options_.components;
  const auto out = head_out_(torch::relu(head_hidden_(torch::relu(skip))));  // [N, D, 3K]
  return {out.narrow(-1, 0, K), out.narrow(-1, K, K),
          soft_bound(out.narrow(-1, 2 * K, K), kMinLogStd, kMaxLogStd)};
}

MixtureParams StateDecoderImpl::forward(const torch::Tensor& prev, const torch::Tensor& next,
                                        const torch::Tensor& z) {
  if (!uses_kernel(next)) return forward_reference(prev, next, z);
  const auto skip =
      wavenet_stack_kernel(shifted_inputs(next).contiguous(), conditioning(prev, z),
                           stack_weights());
  return head(skip);
}

MixtureParams StateDecoderImpl::forward_reference(const torch::Tensor& prev,
                                                  const torch::Tensor& next,
                                                  const torch::Tensor& z) {
  namespace F = torch::nn::functional;
  const int64_t C = options_.channels;
  const auto cond = conditioning(prev, z);                             // [N, L, 2C]
  auto h = F::conv1d(shifted_inputs(next).unsqueeze(1), in_weight_.view({C, 1, 1}),
                     F::Conv1dFuncOptions().bias(in_bias_));           // [N, C, D]
  torch::Tensor skip;
  for (int64_t l = 0; l < options_.layers; ++l) {
    const int64_t d = dilations_[l];
    const auto w = gate_weight_[l];  // columns: tap k | tap k - d
    const auto kernel = torch::stack({w.narrow(1, C, C), w.narrow(1, 0, C)}, 2);  // [2C, C, 2]
    auto a = F::conv1d(F::pad(h, F::PadFuncOptions({d, 0})), kernel,
                       F::Conv1dFuncOptions().dilation(d));           // [N, 2C, D]
    a = a + cond.select(1, l).unsqueeze(-1) + gate_bias_[l].t().unsqueeze(0);
    const auto g = torch::tanh(a.narrow(1, 0, C)) * torch::sigmoid(a.narrow(1, C, C));
    const auto o = F::conv1d(g, out_weight_[l].unsqueeze(-1),
                             F::Conv1dFuncOptions().bias(out_bias_[l]));  // [N, 2C, D]
    skip = l == 0 ? o.narrow(1, C, C) : skip + o.narrow(1, C, C);
    if (l + 1 < options_.layers) h = h + o.narrow(1, 0, C);
  }
  return head(skip.permute({0, 2, 1}));
}

torch::Tensor StateDecoderImpl::log_prob(const torch::Tensor& prev, const torch::Tensor& next,
                                         const torch::Tensor& z) {
  return mixture_log_prob(next, forward(prev, next, z));
}

torch::Tensor StateDecoderImpl::sample(const torch::Tensor& prev, const torch::Tensor& z,
                                       c10::optional<at::Generator> generator) {
  torch::NoGradGuard no_grad;
  auto x = torch::zeros_like(prev);
  for (int64_t k = 0; k < options_.state_dim; ++k) {
    const auto m = forward(prev, x, z);
    const auto at_k = MixtureParams{m.logits.select(1, k), m.means.select(1, k),
                                    m.log_stds.select(1, k)};
    x.select(1, k).copy_(mixture_sample(at_k, generator));
  }
  return x;
}

}  // namespace vaegail::vae
