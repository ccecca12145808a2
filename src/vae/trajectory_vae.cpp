#include "vae/trajectory_vae.h"

#include "vae/gaussian.h"

namespace vaegail::vae {

namespace {

StateDecoderOptions state_decoder_options(const VaeConfig& c) {
  StateDecoderOptions o;
  o.state_dim = c.state_dim;
  o.cond_dim = c.state_dim + c.latent_dim;
  o.channels = c.wavenet_channels;
  o.layers = c.wavenet_layers;
  o.components = c.mixture_components;
  o.position_embedding = c.position_embedding;
  return o;
}

// Mean and std over the leading dims of x [..., F] where `valid` [...] is true.
std::pair<torch::Tensor, torch::Tensor> masked_moments(const torch::Tensor& x,
                                                       const torch::Tensor& valid) {
  const auto flat = x.reshape({-1, x.size(-1)}).to(torch::kDouble);
  const auto rows = valid.defined() ? flat.index({valid.reshape({-1}).to(torch::kBool)}) : flat;
  TORCH_CHECK(rows.size(0) > 0, "fit_normalization: no real steps");
  const auto mean = rows.mean(0);
  auto std = (rows - mean).square().mean(0).sqrt();
  std = torch::where(std < 1e-6, torch::ones_like(std), std);
  return {mean.to(torch::kFloat), std.to(torch::kFloat)};
}

}  // namespace

torch::Tensor state_mask_from_step_mask(const torch::Tensor& step_mask) {
  const auto m = step_mask.to(torch::kBool);
  return torch::cat({torch::ones({m.size(0), 1}, m.options()), m}, 1);
}

TrajectoryVaeImpl::TrajectoryVaeImpl(const VaeConfig& config) : config_(config) {
  config_.validate();
  encoder_ = register_module(
      "encoder", TrajectoryEncoder(config_.encoder_state_indices.empty()
                                       ? config_.state_dim
                                       : static_cast<int>(config_.encoder_state_indices.size()),
                                   config_.lstm_hidden, config_.latent_dim));
  action_decoder_ = register_module(
      "action_decoder", ActionDecoder(config_.state_dim, config_.latent_dim, config_.action_dim,
                                      config_.action_hidden, config_.action_std_depends_on_state));
  state_decoder_ = register_module("state_decoder", StateDecoder(state_decoder_options(config_)));
  state_mean_ = register_buffer("state_mean", torch::zeros({config_.state_dim}));
  state_std_ = register_buffer("state_std", torch::ones({config_.state_dim}));
  action_mean_ = register_buffer("action_mean", torch::zeros({config_.action_dim}));
  action_std_ = register_buffer("action_std", torch::ones({config_.action_dim}));
  const auto& k = config_.action_relative_to_state;
  if (!k.empty()) offset_index_ = torch::tensor(std::vector<int64_t>(k.begin(), k.end()), torch::kLong);
  const auto& e = config_.encoder_state_indices;
  if (!e.empty()) encoder_index_ = torch::tensor(std::vector<int64_t>(e.begin(), e.end()), torch::kLong);
}

torch::Tensor TrajectoryVaeImpl::modelled_actions(const torch::Tensor& states,
                                                  const torch::Tensor& actions) const {
  if (config_.action_relative_to_state.empty()) return actions;
  return actions - action_offset(states.narrow(1, 0, actions.size(1)));
}

torch::Tensor TrajectoryVaeImpl::action_offset(const torch::Tensor& state) const {
  if (!offset_index_.defined()) return torch::zeros({}, state.options());
  return state.index_select(-1, offset_index_.to(state.device()));
}

void TrajectoryVaeImpl::fit_normalization(const torch::Tensor& states,
                                          const torch::Tensor& actions,
                                          const torch::Tensor& mask) {
  const auto s = masked_moments(states, mask.defined() ? state_mask_from_step_mask(mask)
                                                       : torch::Tensor());
  const auto a = masked_moments(modelled_actions(states, actions), mask);
  set_normalization(s.first, s.second, a.first, a.second);
}

void TrajectoryVaeImpl::set_normalization(const torch::Tensor& state_mean,
                                          const torch::Tensor& state_std,
                                          const torch::Tensor& action_mean,
                                          const torch::Tensor& action_std) {
  torch::NoGradGuard no_grad;
  TORCH_CHECK(state_mean.numel() == config_.state_dim && state_std.numel() == config_.state_dim &&
                  action_mean.numel() == config_.action_dim &&
                  action_std.numel() == config_.action_dim,
              "set_normalization: sizes must match state_dim and action_dim");
  TORCH_CHECK((state_std > 0).all().item<bool>() && (action_std > 0).all().item<bool>(),
              "set_normalization: stds must be positive");
  state_mean_.copy_(state_mean.reshape({-1}));
  state_std_.copy_(state_std.reshape({-1}));
  action_mean_.copy_(action_mean.reshape({-1}));
  action_std_.copy_(action_std.reshape({-1}));
}

torch::Tensor TrajectoryVaeImpl::normalize_states(const torch::Tensor& states) const {
  return (states - state_mean_) / state_std_;
}

torch::Tensor TrajectoryVaeImpl::policy_input(const torch::Tensor& x) const {
  if (config_.policy_state_std_floor <= 0) return x;
  return x * (state_std_ / state_std_.clamp_min(config_.policy_state_std_floor));
}

void TrajectoryVaeImpl::set_policy_state_std_floor(double floor) {
  TORCH_CHECK(floor >= 0, "policy_state_std_floor must be >= 0");
  config_.policy_state_std_floor = floor;
}

torch::Tensor TrajectoryVaeImpl::normalize_actions(const torch::Tensor& actions) const {
  return (actions - action_mean_) / action_std_;
}

double TrajectoryVaeImpl::state_log_jacobian() const {
  return -state_std_.log().sum().item<double>();
}

double TrajectoryVaeImpl::action_log_jacobian() const {
  return -action_std_.log().sum().item<double>();
}

torch::Tensor TrajectoryVaeImpl::encoder_input(const torch::Tensor& x, const torch::Tensor& state_mask,
                                               const torch::Tensor& noise) const {
  const auto noisy = noise.defined() ? x + config_.encoder_input_noise * noise : x;
  auto in = encoder_index_.defined() ? noisy.index_select(2, encoder_index_.to(x.device())) : noisy;
  if (state_mask.defined())
    in = torch::where(state_mask.to(torch::kBool).unsqueeze(-1), in, torch::zeros_like(in));
  return in;
}

EncoderOutput TrajectoryVaeImpl::encode(const torch::Tensor& states,
                                        const torch::Tensor& state_mask) {
  return encoder_->forward(encoder_input(normalize_states(states), state_mask, {}), state_mask);
}

TrajectoryVaeImpl::Prepared TrajectoryVaeImpl::prepare(const torch::Tensor& states, const torch::Tensor& actions,
                                                       const torch::Tensor& mask) const {
  TORCH_CHECK(states.dim() == 3 && actions.dim() == 3 && states.size(0) == actions.size(0) &&
                  states.size(1) == actions.size(1) + 1 &&
                  states.size(2) == config_.state_dim && actions.size(2) == config_.action_dim,
              "TrajectoryVae: states must be [B, T+1, D] and actions [B, T, A]");
  const int64_t B = actions.size(0), T = actions.size(1);
  Prepared p{normalize_states(states), normalize_actions(modelled_actions(states, actions)), {}, {}};
  if (mask.defined()) {
    TORCH_CHECK(mask.sizes() == torch::IntArrayRef({B, T}), "TrajectoryVae: mask must be [B, T]");
    p.step_mask = mask.to(states.device()).to(torch::kBool);
    p.state_mask = state_mask_from_step_mask(p.step_mask);
    // Zero the padding so that nothing in it (even NaN) reaches a value or a gradient.
    p.x = torch::where(p.state_mask.unsqueeze(-1), p.x, torch::zeros_like(p.x));
    p.a = torch::where(p.step_mask.unsqueeze(-1), p.a, torch::zeros_like(p.a));
  }
  return p;
}

DecoderNll TrajectoryVaeImpl::decoder_nll(const Prepared& p, const torch::Tensor& z) {
  const int64_t B = p.a.size(0), T = p.a.size(1), D = config_.state_dim, Z = config_.latent_dim;
  TORCH_CHECK(z.sizes() == torch::IntArrayRef({B, Z}), "TrajectoryVae: z must be [B, Z]");
  const auto x_t = p.x.narrow(1, 0, T);
  const auto z_t = z.unsqueeze(1).expand({B, T, Z});
  const auto action_lp = action_decoder_->log_prob(policy_input(x_t), z_t, p.a);  // [B, T]
  const auto state_lp = state_decoder_
                            ->log_prob(x_t.reshape({B * T, D}), p.x.narrow(1, 1, T).reshape({B * T, D}),
                                       z_t.reshape({B * T, Z}))
                            .sum(-1)
                            .view({B, T});
  auto per_step_action = action_lp, per_step_state = state_lp;
  if (p.step_mask.defined()) {
    per_step_action = torch::where(p.step_mask, action_lp, torch::zeros_like(action_lp));
    per_step_state = torch::where(p.step_mask, state_lp, torch::zeros_like(state_lp));
  }
  return {-per_step_action.sum(1), -per_step_state.sum(1)};
}

DecoderNll TrajectoryVaeImpl::decoder_nll(const torch::Tensor& states, const torch::Tensor& actions,
                                          const torch::Tensor& z, const torch::Tensor& mask) {
  return decoder_nll(prepare(states, actions, mask), z);
}

VaeLoss TrajectoryVaeImpl::loss(const torch::Tensor& states, const torch::Tensor& actions,
                                const torch::Tensor& mask, const torch::Tensor& noise,
                                const torch::Tensor& encoder_noise) {
  const auto p = prepare(states, actions, mask);
  torch::Tensor input_noise;
  if (is_training() && config_.encoder_input_noise > 0) {
    input_noise = encoder_noise.defined() ? encoder_noise.to(p.x.device()) : torch::randn_like(p.x);
    TORCH_CHECK(input_noise.sizes() == p.x.sizes(), "TrajectoryVae::loss: encoder_noise must be [B, T+1, D]");
  }
  const auto q = encoder_->forward(encoder_input(p.x, p.state_mask, input_noise), p.state_mask);
  const auto eps = noise.defined() ? noise.to(q.mean.device()) : torch::randn_like(q.mean);
  TORCH_CHECK(eps.sizes() == q.mean.sizes(), "TrajectoryVae::loss: noise must be [B, Z]");
  const auto nll = decoder_nll(p, reparameterize(q.mean, q.log_std, eps));
  const auto kl = kl_to_standard_normal(q.mean, q.log_std);
  const auto per_trajectory = nll.action + nll.state + config_.kl_weight * kl;
  return {per_trajectory.mean(), nll.action.mean(), nll.state.mean(), kl.mean(), per_trajectory};
}

torch::Tensor TrajectoryVaeImpl::action_mean(const torch::Tensor& state, const torch::Tensor& z) {
  return action_decoder_->mean(policy_input(normalize_states(state)), z) * action_std_ + action_mean_ +
         action_offset(state);
}

torch::Tensor TrajectoryVaeImpl::sample_next_state(const torch::Tensor& state,
                                                   const torch::Tensor& z,
                                                   c10::optional<at::Generator> generator) {
  const auto next = state_decoder_->sample(normalize_states(state), z, generator);
  return next * state_std_ + state_mean_;
}

}  // namespace vaegail::vae
