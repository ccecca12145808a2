#include "vae/state_decoder_kernel.h"

#include <ATen/Parallel.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>

namespace vaegail::vae {

namespace {

// ---------------------------------------------------------------------------------------
// Elementwise loops. Each is compiled for AVX-512, AVX2+FMA and baseline x86-64; the loader
// picks the best the CPU has. tanh and sigmoid use a polynomial exp (Cephes expf, ~1 ulp)
// that the compiler can vectorise, unlike libm's expf.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define VAE_VECTOR_CLONES \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define VAE_VECTOR_CLONES
#endif

inline __attribute__((always_inline)) float exp_approx(float x) {
  x = x < -87.0f ? -87.0f : (x > 88.0f ? 88.0f : x);
  const float n = (x * 1.44269504088896341f + 12582912.0f) - 12582912.0f;  // round(x / ln 2)
  const float r = x - n * 0.693359375f + n * 2.12194440e-4f;              // x - n ln 2
  float p = 1.9875691500e-4f;
  p = p * r + 1.3981999507e-3f;
  p = p * r + 8.3334519073e-3f;
  p = p * r + 4.1665795894e-2f;
  p = p * r + 1.6666665459e-1f;
  p = p * r + 5.0000001201e-1f;
  p = p * r * r + r + 1.0f;
  const int32_t bits = (static_cast<int32_t>(n) + 127) << 23;  // 2^n
  float scale;
  std::memcpy(&scale, &bits, sizeof scale);
  return p * scale;
}

inline __attribute__((always_inline)) float tanh_approx(float x) {
  return 1.0f - 2.0f / (exp_approx(2.0f * x) + 1.0f);
}

inline __attribute__((always_inline)) float sigmoid_approx(float x) {
  return 1.0f / (1.0f + exp_approx(-x));
}

// H[r, c] = u[r] * w[c] + b[c]
VAE_VECTOR_CLONES void input_projection(const float* __restrict u, int64_t rows,
                                        const float* __restrict w, const float* __restrict b,
                                        int64_t C, float* __restrict H) {
  for (int64_t r = 0; r < rows; ++r)
    for (int64_t c = 0; c < C; ++c) H[r * C + c] = u[r] * w[c] + b[c];
}

// Z[(n, k), :] = [H[(n, k), :] | H[(n, k - d), :] or 0 when k < d]
VAE_VECTOR_CLONES void build_taps(const float* __restrict H, int64_t positions, int64_t D,
                                  int64_t C, int64_t d, float* __restrict Z) {
  for (int64_t n = 0; n < positions; ++n)
    for (int64_t k = 0; k < D; ++k) {
      const int64_t r = n * D + k;
      float* __restrict z = Z + r * 2 * C;
      const float* __restrict h = H + r * C;
      for (int64_t c = 0; c < C; ++c) z[c] = h[c];
      if (k >= d) {
        const float* __restrict past = H + (r - d) * C;
        for (int64_t c = 0; c < C; ++c) z[C + c] = past[c];
      } else {
        for (int64_t c = 0; c < C; ++c) z[C + c] = 0.0f;
      }
    }
}

// a = A[(n,k)] + cond[n] + P[k]; TS = (tanh a_f, sigmoid a_g); G = tanh a_f * sigmoid a_g
VAE_VECTOR_CLONES void gate_forward(const float* __restrict A, const float* __restrict cond,
                                    int64_t cond_stride, const float* __restrict P,
                                    int64_t P_stride, int64_t positions, int64_t D, int64_t C,
                                    float* __restrict TS, float* __restrict G) {
  for (int64_t n = 0; n < positions; ++n) {
    const float* __restrict cf = cond + n * cond_stride;
    for (int64_t k = 0; k < D; ++k) {
      const int64_t r = n * D + k;
      const float* __restrict a = A + r * 2 * C;
      const float* __restrict p = P + k * P_stride;
      float* __restrict ts = TS + r * 2 * C;
      float* __restrict g = G + r * C;
      for (int64_t c = 0; c < C; ++c) {
        const float t = tanh_approx(a[c] + cf[c] + p[c]);
        const float s = sigmoid_approx(a[C + c] + cf[C + c] + p[C + c]);
        ts[c] = t;
        ts[C + c] = s;
        g[c] = t * s;
      }
    }
  }
}

// H_next = H + O[:, :C] + b[:C] (when H_next is given); S (=|+=) O[:, C:] + b[C:]
VAE_VECTOR_CLONES void residual_and_skip(const float* __restrict H, const float* __restrict O,
                                         const float* __restrict b, int64_t rows, int64_t C,
                                         bool first_layer, float* __restrict H_next,
                                         float* __restrict S) {
  for (int64_t r = 0; r < rows; ++r) {
    const float* __restrict o = O + r * 2 * C;
    if (H_next != nullptr) {
      for (int64_t c = 0; c < C; ++c) H_next[r * C + c] = H[r * C + c] + o[c] + b[c];
    }
    float* __restrict s = S + r * C;
    if (first_layer) {
      for (int64_t c = 0; c < C; ++c) s[c] = o[C + c] + b[C + c];
    } else {
      for (int64_t c = 0; c < C; ++c) s[c] += o[C + c] + b[C + c];
    }
  }
}

// G = t * s
VAE_VECTOR_CLONES void gate_product(const float* __restrict TS, int64_t rows, int64_t C,
                                    float* __restrict G) {
  for (int64_t r = 0; r < rows; ++r)
    for (int64_t c = 0; c < C; ++c) G[r * C + c] = TS[r * 2 * C + c] * TS[r * 2 * C + C + c];
}

// acc[c] += sum_r X[r, c] for a [rows, cols] block with row stride ld
VAE_VECTOR_CLONES void add_column_sums(const float* __restrict X, int64_t rows, int64_t cols,
                                       int64_t ld, float* __restrict acc) {
  for (int64_t r = 0; r < rows; ++r)
    for (int64_t c = 0; c < cols; ++c) acc[c] += X[r * ld + c];
}

// dA = (dG s (1 - t^2), dG t s (1 - s)); dcond[n] = sum_k dA; dP[k] += dA (P_stride 0: all k)
VAE_VECTOR_CLONES void gate_backward(const float* __restrict dG, const float* __restrict TS,
                                     int64_t positions, int64_t D, int64_t C,
                                     float* __restrict dA, float* __restrict dcond,
                                     int64_t dcond_stride, float* __restrict dP,
                                     int64_t P_stride) {
  for (int64_t n = 0; n < positions; ++n) {
    float* __restrict dc = dcond + n * dcond_stride;
    for (int64_t c = 0; c < 2 * C; ++c) dc[c] = 0.0f;
    for (int64_t k = 0; k < D; ++k) {
      const int64_t r = n * D + k;
      const float* __restrict ts = TS + r * 2 * C;
      const float* __restrict g = dG + r * C;
      float* __restrict da = dA + r * 2 * C;
      float* __restrict dp = dP + k * P_stride;
      for (int64_t c = 0; c < C; ++c) {
        const float t = ts[c], s = ts[C + c];
        const float df = g[c] * s * (1.0f - t * t);
        const float dg = g[c] * t * s * (1.0f - s);
        da[c] = df;
        da[C + c] = dg;
        dc[c] += df;
        dc[C + c] += dg;
        dp[c] += df;
        dp[C + c] += dg;
      }
    }
  }
}

// dH[(n,k)] += dZ[(n,k), :C] + dZ[(n,k+d), C:] (second term only when k + d < D);
// dH has row stride ld (it is the left half of the [rows, 2C] buffer dHS).
VAE_VECTOR_CLONES void accumulate_tap_gradients(const float* __restrict dZ, int64_t positions,
                                                int64_t D, int64_t C, int64_t d,
                                                float* __restrict dH, int64_t ld) {
  for (int64_t n = 0; n < positions; ++n)
    for (int64_t k = 0; k < D; ++k) {
      const int64_t r = n * D + k;
      float* __restrict h = dH + r * ld;
      const float* __restrict now = dZ + r * 2 * C;
      for (int64_t c = 0; c < C; ++c) h[c] += now[c];
      if (k + d < D) {
        const float* __restrict later = dZ + (r + d) * 2 * C + C;
        for (int64_t c = 0; c < C; ++c) h[c] += later[c];
      }
    }
}

// dw[c] += sum_r dH[r, c] u[r];  db[c] += sum_r dH[r, c]
VAE_VECTOR_CLONES void input_projection_backward(const float* __restrict dH, int64_t ld,
                                                 const float* __restrict u, int64_t rows,
                                                 int64_t C, float* __restrict dw,
                                                 float* __restrict db) {
  for (int64_t r = 0; r < rows; ++r)
    for (int64_t c = 0; c < C; ++c) {
      dw[c] += dH[r * ld + c] * u[r];
      db[c] += dH[r * ld + c];
    }
}

// ---------------------------------------------------------------------------------------
// Row-major GEMM on raw pointers: C = alpha op(A) op(B) + beta C, through ATen's addmm_out
// (the BLAS underneath; ~2-5 us of dispatch per call, small next to a chunk's work).
void gemm(bool trans_a, bool trans_b, int64_t m, int64_t n, int64_t k, const float* A,
          int64_t lda, const float* B, int64_t ldb, float beta, float* C, int64_t ldc) {
  const auto opts = torch::TensorOptions().dtype(torch::kFloat);
  auto a = trans_a ? torch::from_blob(const_cast<float*>(A), {m, k}, {1, lda}, opts)
                   : torch::from_blob(const_cast<float*>(A), {m, k}, {lda, 1}, opts);
  auto b = trans_b ? torch::from_blob(const_cast<float*>(B), {k, n}, {1, ldb}, opts)
                   : torch::from_blob(const_cast<float*>(B), {k, n}, {ldb, 1}, opts);
  auto c = torch::from_blob(C, {m, n}, {ldc, 1}, opts);
  if (beta == 0.0f) {
    at::mm_out(c, a, b);
  } else {
    at::addmm_out(c, c, a, b, beta, 1.0f);
  }
}

std::atomic<int64_t> chunk_positions_override{0};

struct Dims {
  int64_t N, D, C, L, P;
};

// Scratch for one chunk; one per thread.
struct Workspace {
  explicit Workspace(int64_t rows, int64_t C)
      : Z(torch::empty({rows, 2 * C})),
        A(torch::empty({rows, 2 * C})),
        G(torch::empty({rows, C})),
        O(torch::empty({rows, 2 * C})) {}
  torch::Tensor Z, A, G, O;
};

// Calls fn(first_position, positions, thread_index) for every chunk, the chunks split into
// one contiguous run per thread.
template <class Fn>
void for_each_chunk(int64_t N, int64_t chunk, int threads, const Fn& fn) {
  const int64_t chunks = (N + chunk - 1) / chunk;
  const int64_t per_thread = (chunks + threads - 1) / threads;
  at::parallel_for(0, threads, 1, [&](int64_t begin, int64_t end) {
    for (int64_t t = begin; t < end; ++t)
      for (int64_t c = t * per_thread; c < std::min(chunks, (t + 1) * per_thread); ++c) {
        const int64_t n0 = c * chunk;
        fn(n0, std::min(chunk, N - n0), static_cast<int>(t));
      }
  });
}

class WaveNetStackFunction : public torch::autograd::Function<WaveNetStackFunction> {
 public:
  static torch::Tensor forward(torch::autograd::AutogradContext* ctx, torch::Tensor inputs,
                               torch::Tensor cond, torch::Tensor in_weight,
                               torch::Tensor in_bias, torch::Tensor gate_weight,
                               torch::Tensor gate_bias, torch::Tensor out_weight,
                               torch::Tensor out_bias, std::vector<int64_t> dilations) {
    inputs = inputs.contiguous();
    cond = cond.contiguous();
    in_weight = in_weight.contiguous();
    in_bias = in_bias.contiguous();
    gate_weight = gate_weight.contiguous();
    gate_bias = gate_bias.contiguous();
    out_weight = out_weight.contiguous();
    out_bias = out_bias.contiguous();
    const Dims dm{inputs.size(0), inputs.size(1), in_weight.size(0), gate_weight.size(0),
                  gate_bias.size(1)};
    const int64_t R = dm.N * dm.D, C = dm.C, D = dm.D;
    // Saved for backward: H_l [L, R, C] and (tanh, sigmoid) [L, R, 2C].
    auto H = torch::empty({dm.L, R, C});
    auto TS = torch::empty({dm.L, R, 2 * C});
    auto S = torch::empty({dm.N, D, C});

    const int64_t chunk = wavenet_chunk_positions(D);
    const int threads = static_cast<int>(
        std::max<int64_t>(1, std::min<int64_t>(at::get_num_threads(), (dm.N + chunk - 1) / chunk)));
    std::vector<Workspace> ws;
    for (int t = 0; t < threads; ++t) ws.emplace_back(chunk * D, C);

    const float* u = inputs.data_ptr<float>();
    const float* cnd = cond.data_ptr<float>();
    const float* Wg = gate_weight.data_ptr<float>();
    const float* Pb = gate_bias.data_ptr<float>();
    const float* Wo = out_weight.data_ptr<float>();
    const float* bo = out_bias.data_ptr<float>();
    float* Hp = H.data_ptr<float>();
    float* TSp = TS.data_ptr<float>();
    float* Sp = S.data_ptr<float>();

    for_each_chunk(dm.N, chunk, threads, [&](int64_t n0, int64_t np, int t) {
      Workspace& w = ws[t];
      float* Z = w.Z.data_ptr<float>();
      float* A = w.A.data_ptr<float>();
      float* G = w.G.data_ptr<float>();
      float* O = w.O.data_ptr<float>();
      const int64_t r0 = n0 * D, rows = np * D;
      input_projection(u + r0, rows, in_weight.data_ptr<float>(), in_bias.data_ptr<float>(), C,
                       Hp + r0 * C);
      for (int64_t l = 0; l < dm.L; ++l) {
        const float* Hl = Hp + (l * R + r0) * C;
        float* TSl = TSp + (l * R + r0) * 2 * C;
        build_taps(Hl, np, D, C, dilations[l], Z);
        gemm(false, true, rows, 2 * C, 2 * C, Z, 2 * C, Wg + l * 4 * C * C, 2 * C, 0.0f, A,
             2 * C);
        gate_forward(A, cnd + (n0 * dm.L + l) * 2 * C, dm.L * 2 * C, Pb + l * dm.P * 2 * C,
                     dm.P == 1 ? 0 : 2 * C, np, D, C, TSl, G);
        gemm(false, true, rows, 2 * C, C, G, C, Wo + l * 2 * C * C, C, 0.0f, O, 2 * C);
        float* H_next = l + 1 < dm.L ? Hp + ((l + 1) * R + r0) * C : nullptr;
        residual_and_skip(Hl, O, bo + l * 2 * C, rows, C, l == 0, H_next, Sp + r0 * C);
      }
    });

    ctx->save_for_backward({inputs, gate_weight, out_weight});
    ctx->saved_data["H"] = H;
    ctx->saved_data["TS"] = TS;
    ctx->saved_data["dilations"] = dilations;
    ctx->saved_data["P"] = dm.P;
    return S;
  }

  static torch::autograd::variable_list backward(torch::autograd::AutogradContext* ctx,
                                                 torch::autograd::variable_list grad_outputs) {
    const auto saved = ctx->get_saved_variables();
    const auto& inputs = saved[0];
    const auto& gate_weight = saved[1];
    const auto& out_weight = saved[2];
    const auto H = ctx->saved_data["H"].toTensor();
    const auto TS = ctx->saved_data["TS"].toTensor();
    const auto dilations = ctx->saved_data["dilations"].toIntVector();
    const Dims dm{inputs.size(0), inputs.size(1), gate_weight.size(1) / 2, gate_weight.size(0),
                  ctx->saved_data["P"].toInt()};
    const int64_t R = dm.N * dm.D, C = dm.C, D = dm.D, L = dm.L;
    const auto dS = grad_outputs[0].contiguous();

    auto d_cond = torch::empty({dm.N, L, 2 * C});
    const int64_t chunk = wavenet_chunk_positions(D);
    const int threads = static_cast<int>(
        std::max<int64_t>(1, std::min<int64_t>(at::get_num_threads(), (dm.N + chunk - 1) / chunk)));
    // Per-thread weight-gradient accumulators, summed in thread order at the end.
    struct Grads {
      torch::Tensor in_w, in_b, gate_w, gate_b, out_w, out_b;
    };
    std::vector<Grads> grads;
    std::vector<Workspace> ws;
    for (int t = 0; t < threads; ++t) {
      grads.push_back({torch::zeros({C}), torch::zeros({C}), torch::zeros({L, 2 * C, 2 * C}),
                       torch::zeros({L, dm.P, 2 * C}), torch::zeros({L, 2 * C, C}),
                       torch::zeros({L, 2 * C})});
      ws.emplace_back(chunk * D, C);
    }
    std::vector<torch::Tensor> dHS;
    for (int t = 0; t < threads; ++t) dHS.push_back(torch::empty({chunk * D, 2 * C}));

    const float* u = inputs.data_ptr<float>();
    const float* Wg = gate_weight.data_ptr<float>();
    const float* Wo = out_weight.data_ptr<float>();
    const float* Hp = H.data_ptr<float>();
    const float* TSp = TS.data_ptr<float>();
    const float* dSp = dS.data_ptr<float>();
    float* dcp = d_cond.data_ptr<float>();

    for_each_chunk(dm.N, chunk, threads, [&](int64_t n0, int64_t np, int t) {
      Workspace& w = ws[t];
      Grads& g = grads[t];
      float* Z = w.Z.data_ptr<float>();
      float* dA = w.A.data_ptr<float>();
      float* G = w.G.data_ptr<float>();
      float* dZ = w.O.data_ptr<float>();
      float* dG = G;  // G is dead once dW_out is accumulated
      float* dO = dHS[t].data_ptr<float>();  // [rows, 2C]: dH | dS
      const int64_t r0 = n0 * D, rows = np * D;
      for (int64_t r = 0; r < rows; ++r) {
        std::memset(dO + r * 2 * C, 0, C * sizeof(float));
        std::memcpy(dO + r * 2 * C + C, dSp + (r0 + r) * C, C * sizeof(float));
      }
      for (int64_t l = L - 1; l >= 0; --l) {
        const float* Hl = Hp + (l * R + r0) * C;
        const float* TSl = TSp + (l * R + r0) * 2 * C;
        gate_product(TSl, rows, C, G);
        // dW_out += dO^T G;  db_out += colsum(dO);  dG = dO W_out
        gemm(true, false, 2 * C, C, rows, dO, 2 * C, G, C, 1.0f,
             g.out_w.data_ptr<float>() + l * 2 * C * C, C);
        add_column_sums(dO, rows, 2 * C, 2 * C, g.out_b.data_ptr<float>() + l * 2 * C);
        gemm(false, false, rows, C, 2 * C, dO, 2 * C, Wo + l * 2 * C * C, C, 0.0f, dG, C);
        gate_backward(dG, TSl, np, D, C, dA, dcp + (n0 * L + l) * 2 * C, L * 2 * C,
                      g.gate_b.data_ptr<float>() + l * dm.P * 2 * C, dm.P == 1 ? 0 : 2 * C);
        // dW_gate += dA^T Z;  dZ = dA W_gate;  dH += dZ_now + unshift(dZ_past)
        build_taps(Hl, np, D, C, dilations[l], Z);
        gemm(true, false, 2 * C, 2 * C, rows, dA, 2 * C, Z, 2 * C, 1.0f,
             g.gate_w.data_ptr<float>() + l * 4 * C * C, 2 * C);
        gemm(false, false, rows, 2 * C, 2 * C, dA, 2 * C, Wg + l * 4 * C * C, 2 * C, 0.0f, dZ,
             2 * C);
        accumulate_tap_gradients(dZ, np, D, C, dilations[l], dO, 2 * C);
      }
      input_projection_backward(dO, 2 * C, u + r0, rows, C, g.in_w.data_ptr<float>(),
                                g.in_b.data_ptr<float>());
    });

    for (int t = 1; t < threads; ++t) {
      grads[0].in_w += grads[t].in_w;
      grads[0].in_b += grads[t].in_b;
      grads[0].gate_w += grads[t].gate_w;
      grads[0].gate_b += grads[t].gate_b;
      grads[0].out_w += grads[t].out_w;
      grads[0].out_b += grads[t].out_b;
    }
    const Grads& g = grads[0];
    return {torch::Tensor(), d_cond, g.in_w, g.in_b, g.gate_w, g.gate_b, g.out_w, g.out_b,
            torch::Tensor()};
  }
};

}  // namespace

void set_wavenet_chunk_positions(int64_t positions) {
  chunk_positions_override.store(std::max<int64_t>(0, positions));
}

int64_t wavenet_chunk_positions(int64_t state_dim) {
  const int64_t forced = chunk_positions_override.load();
  if (forced > 0) return forced;
  // ~2048 rows: the chunk's [rows, 2C] buffers (four of them at C = 32) fit in L2.
  return std::max<int64_t>(1, 2048 / std::max<int64_t>(1, state_dim));
}

bool wavenet_kernel_supports(const torch::Tensor& inputs) {
  return inputs.device().is_cpu() && inputs.scalar_type() == torch::kFloat;
}

torch::Tensor wavenet_stack_kernel(const torch::Tensor& inputs, const torch::Tensor& cond,
                                   const WaveNetStackWeights& w) {
  const int64_t N = inputs.size(0), D = inputs.size(1), C = w.in_weight.size(0);
  const int64_t L = w.gate_weight.size(0);
  TORCH_CHECK(wavenet_kernel_supports(inputs), "wavenet_stack_kernel: needs float32 on the CPU");
  TORCH_CHECK(inputs.dim() == 2, "wavenet_stack_kernel: inputs must be [N, D]");
  TORCH_CHECK(cond.sizes() == torch::IntArrayRef({N, L, 2 * C}),
              "wavenet_stack_kernel: cond must be [N, L, 2C]");
  TORCH_CHECK(w.gate_weight.sizes() == torch::IntArrayRef({L, 2 * C, 2 * C}) &&
                  w.out_weight.sizes() == torch::IntArrayRef({L, 2 * C, C}) &&
                  w.out_bias.sizes() == torch::IntArrayRef({L, 2 * C}) &&
                  w.gate_bias.dim() == 3 && w.gate_bias.size(0) == L &&
                  (w.gate_bias.size(1) == D || w.gate_bias.size(1) == 1) &&
                  w.gate_bias.size(2) == 2 * C,
              "wavenet_stack_kernel: weight shapes do not match C, L, D");
  TORCH_CHECK(static_cast<int64_t>(w.dilations.size()) == L,
              "wavenet_stack_kernel: one dilation per layer");
  for (int64_t d : w.dilations)
    TORCH_CHECK(d >= 1 && (d < D || D == 1), "wavenet_stack_kernel: dilation out of range");
  return WaveNetStackFunction::apply(inputs, cond, w.in_weight, w.in_bias, w.gate_weight,
                                     w.gate_bias, w.out_weight, w.out_bias, w.dilations);
}

}  // namespace vaegail::vae
