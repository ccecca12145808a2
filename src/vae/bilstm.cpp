#include "vae/bilstm.h"

#include <cmath>
#include <string>

namespace vaegail::vae {

namespace {

using torch::autograd::AutogradContext;
using torch::autograd::tensor_list;

// Pointers to the activated gates of one step, [B, 4H] row-major, and the row stride.
struct Gates {
  const float* p;
  int64_t hidden;
  float i(int64_t b, int64_t j) const { return p[b * 4 * hidden + j]; }
  float f(int64_t b, int64_t j) const { return p[b * 4 * hidden + hidden + j]; }
  float g(int64_t b, int64_t j) const { return p[b * 4 * hidden + 2 * hidden + j]; }
  float o(int64_t b, int64_t j) const { return p[b * 4 * hidden + 3 * hidden + j]; }
};

// Pre-activations [B, 4H] -> i, f, o through the sigmoid and g through tanh, in place (ATen's
// vectorised kernels: the transcendental functions are most of the cell's cost).
void activate_gates(const torch::Tensor& gates, int64_t hidden) {
  gates.narrow(1, 0, 2 * hidden).sigmoid_();
  gates.narrow(1, 2 * hidden, hidden).tanh_();
  gates.narrow(1, 3 * hidden, hidden).sigmoid_();
}

// c_t = f * c_{t-1} + i * g, all [B, H] contiguous.
void cell_state(const Gates& gates, const float* c_prev, float* c, int64_t batch) {
  const int64_t H = gates.hidden;
  for (int64_t b = 0; b < batch; ++b)
    for (int64_t j = 0; j < H; ++j)
      c[b * H + j] = gates.f(b, j) * c_prev[b * H + j] + gates.i(b, j) * gates.g(b, j);
}

// One step of the backward pass through time, all [B, H] contiguous except the gates [B, 4H].
// Reads dL/dh_t (the output's gradient plus the recurrent one, dh_out + dh_rec) and dL/dc_t from
// step t + 1 (dc), writes dL/d(pre-activation gates) of step t and replaces dc with dL/dc_{t-1}.
void cell_backward(const Gates& gates, const float* tanh_c, const float* c_prev, const float* dh_out,
                   const float* dh_rec, float* dc, float* d_gates, int64_t batch) {
  const int64_t H = gates.hidden;
  for (int64_t b = 0; b < batch; ++b) {
    float* dg = d_gates + b * 4 * H;
    for (int64_t j = 0; j < H; ++j) {
      const int64_t k = b * H + j;
      const float i = gates.i(b, j), f = gates.f(b, j), g = gates.g(b, j), o = gates.o(b, j);
      const float dh = dh_out[k] + dh_rec[k];
      const float dct = dc[k] + dh * o * (1.0f - tanh_c[k] * tanh_c[k]);
      dg[j] = dct * g * i * (1.0f - i);
      dg[H + j] = dct * c_prev[k] * f * (1.0f - f);
      dg[2 * H + j] = dct * i * (1.0f - g * g);
      dg[3 * H + j] = dh * tanh_c[k] * o * (1.0f - o);
      dc[k] = dct * f;
    }
  }
}

class LstmRecurrence : public torch::autograd::Function<LstmRecurrence> {
 public:
  static torch::Tensor forward(AutogradContext* ctx, const torch::Tensor& gates_in,
                               const torch::Tensor& w_hh) {
    // The cell loops read raw float memory: CPU only (the Debian LibTorch this project builds on is).
    TORCH_CHECK(gates_in.device().is_cpu() && w_hh.device().is_cpu() &&
                    gates_in.scalar_type() == torch::kFloat && w_hh.scalar_type() == torch::kFloat,
                "lstm_recurrence: float CPU tensors only");
    TORCH_CHECK(gates_in.dim() == 3, "lstm_recurrence: gates_in [S, B, 4H]");
    const int64_t S = gates_in.size(0), B = gates_in.size(1), H = w_hh.size(1);
    TORCH_CHECK(gates_in.size(2) == 4 * H && w_hh.size(0) == 4 * H,
                "lstm_recurrence: gates_in [S, B, 4H], w_hh [4H, H]");
    const auto opts = gates_in.options();
    auto gates = torch::empty({S, B, 4 * H}, opts);  // activated, kept for the backward pass
    auto c = torch::empty({S, B, H}, opts), tanh_c = torch::empty({S, B, H}, opts);
    auto h = torch::empty({S, B, H}, opts);
    const auto zero = torch::zeros({B, H}, opts);
    const auto gates_in_c = gates_in.contiguous();
    const auto w_hh_t = w_hh.t();
    for (int64_t t = 0; t < S; ++t) {
      const auto& h_prev = t > 0 ? h[t - 1] : zero;
      const auto& c_prev = t > 0 ? c[t - 1] : zero;
      auto g = gates[t];
      torch::addmm_out(g, gates_in_c[t], h_prev, w_hh_t);
      activate_gates(g, H);
      cell_state({g.data_ptr<float>(), H}, c_prev.data_ptr<float>(), c[t].data_ptr<float>(), B);
      auto tc = tanh_c[t];
      torch::tanh_out(tc, c[t]);
      auto ht = h[t];
      torch::mul_out(ht, g.narrow(1, 3 * H, H), tc);
    }
    ctx->save_for_backward({gates, c, tanh_c, h, w_hh});
    return h;
  }

  static tensor_list backward(AutogradContext* ctx, tensor_list grad_outputs) {
    const auto saved = ctx->get_saved_variables();
    const auto &gates = saved[0], &c = saved[1], &tanh_c = saved[2], &h = saved[3], &w_hh = saved[4];
    const int64_t S = gates.size(0), B = gates.size(1), H = w_hh.size(1);
    const auto dh_out = grad_outputs[0].contiguous();
    auto d_gates = torch::empty_like(gates);
    auto dh_rec = torch::zeros({B, H}, gates.options()), dc = torch::zeros({B, H}, gates.options());
    const auto zero = torch::zeros({B, H}, gates.options());
    for (int64_t t = S - 1; t >= 0; --t) {
      const auto& c_prev = t > 0 ? c[t - 1] : zero;
      auto dg = d_gates[t];
      cell_backward({gates[t].data_ptr<float>(), H}, tanh_c[t].data_ptr<float>(), c_prev.data_ptr<float>(),
                    dh_out[t].data_ptr<float>(), dh_rec.data_ptr<float>(), dc.data_ptr<float>(),
                    dg.data_ptr<float>(), B);
      torch::mm_out(dh_rec, dg, w_hh);  // dL/dh_{t-1} through the recurrent weights
    }
    // All steps' recurrent weight gradients as one GEMM: dW_hh = sum_t dG_t^T h_{t-1}.
    const auto h_prev = torch::cat({zero.unsqueeze(0), h.narrow(0, 0, S - 1)});
    const auto d_w_hh = d_gates.view({S * B, 4 * H}).t().mm(h_prev.view({S * B, H}));
    return {d_gates, d_w_hh};
  }
};

// Row b of a time-major sequence [S, B, F] with its first lengths[b] steps reversed and its padding
// left in place: the backward direction reads each row from its last real step. `index` [S, B] is
// reversal_index(); the map is its own inverse.
torch::Tensor reverse_real_steps(const torch::Tensor& seq, const torch::Tensor& index) {
  return seq.gather(0, index.unsqueeze(2).expand({-1, -1, seq.size(2)}));
}

torch::Tensor reversal_index(const torch::Tensor& lengths, int64_t steps) {
  const auto t = torch::arange(steps, lengths.options()).unsqueeze(1);
  const auto len = lengths.unsqueeze(0);
  return torch::where(t < len, len - 1 - t, t);
}

}  // namespace

torch::Tensor lstm_recurrence(const torch::Tensor& gates_in, const torch::Tensor& w_hh) {
  return LstmRecurrence::apply(gates_in, w_hh);
}

BiLstmImpl::BiLstmImpl(int64_t input_size, int64_t hidden, int64_t layers) {
  // Registered in torch::nn::LSTM's order and initialised as it is (uniform in +-1/sqrt(H), in
  // registration order), so a seed gives the stock module's weights and optimiser states line up.
  for (int64_t l = 0; l < layers; ++l) {
    std::array<Direction, 2> layer;
    for (int d = 0; d < 2; ++d) {
      const auto suffix = std::to_string(l) + (d == 1 ? "_reverse" : "");
      const int64_t in = l == 0 ? input_size : 2 * hidden;
      layer[d].w_ih = register_parameter("weight_ih_l" + suffix, torch::empty({4 * hidden, in}));
      layer[d].w_hh = register_parameter("weight_hh_l" + suffix, torch::empty({4 * hidden, hidden}));
      layer[d].b_ih = register_parameter("bias_ih_l" + suffix, torch::empty({4 * hidden}));
      layer[d].b_hh = register_parameter("bias_hh_l" + suffix, torch::empty({4 * hidden}));
    }
    layers_.push_back(layer);
  }
  const double bound = 1.0 / std::sqrt(static_cast<double>(hidden));
  torch::NoGradGuard no_grad;
  for (auto& p : parameters()) p.uniform_(-bound, bound);
}

torch::Tensor BiLstmImpl::forward(const torch::Tensor& x, const torch::Tensor& lengths) {
  TORCH_CHECK(x.dim() == 3 && lengths.dim() == 1 && lengths.size(0) == x.size(0),
              "BiLstm: x [B, S, D], lengths [B]");
  const int64_t S = x.size(1), B = x.size(0);
  const auto len = lengths.to(x.device(), torch::kLong);
  const auto real =
      (torch::arange(S, len.options()).unsqueeze(1) < len.unsqueeze(0)).unsqueeze(2);  // [S, B, 1]
  const auto reversed = reversal_index(len, S);
  // Time-major, padding zeroed: padded steps are computed (a row's later steps cannot reach its
  // earlier ones), but they never read the caller's padding values and their outputs are dropped.
  auto input = x.transpose(0, 1).masked_fill(real.logical_not(), 0.0).contiguous();
  for (const auto& layer : layers_) {
    std::array<torch::Tensor, 2> out;
    for (int d = 0; d < 2; ++d) {
      const auto& p = layer[d];
      const auto in = d == 0 ? input : reverse_real_steps(input, reversed);
      const auto gates_in = torch::addmm(p.b_ih + p.b_hh, in.reshape({S * B, in.size(2)}), p.w_ih.t());
      const auto h = lstm_recurrence(gates_in.view({S, B, -1}), p.w_hh);
      out[d] = d == 0 ? h : reverse_real_steps(h, reversed);
    }
    input = torch::cat({out[0], out[1]}, 2);
  }
  return input.masked_fill(real.logical_not(), 0.0).transpose(0, 1);
}

}  // namespace vaegail::vae
