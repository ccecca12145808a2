// The fast CPU kernel of the state decoder's WaveNet stack (see state_decoder.h for the model
// and README.md for the design and measurements).
//
// With kernel size 2, a dilated causal convolution over the D components of one position is
// two matrix products. Activations are kept as row-major [rows, C] matrices, one row per
// (position n, component k), rows = N * D, and layer l computes
//
//   Z      = [H | shift_d(H)]                       [rows, 2C]   (shift within each position)
//   A      = Z W_l^T + cond_l[n] + P_l[k]            [rows, 2C]   one GEMM, K = N = 2C
//   G      = tanh(A[:, :C]) * sigmoid(A[:, C:])      [rows, C]
//   O      = G U_l^T + b_l                           [rows, 2C]   one GEMM: residual | skip
//   H'     = H + O[:, :C],   S += O[:, C:]
//
// Every operation is local to one position, so the N positions are processed in chunks that
// stay in L2 cache through all layers, forward and backward, with the gradients of the
// weights accumulated chunk by chunk (one accumulator per thread, summed in thread order:
// results are deterministic for a given thread count). The elementwise work is fused into
// a few loops with vectorised tanh/sigmoid (AVX-512 / AVX2 clones chosen at load time).
// The forward pass keeps H and (tanh, sigmoid) of every layer for the backward pass:
// 3C floats per row and layer.
#pragma once

#include <torch/torch.h>

#include <vector>

namespace vaegail::vae {

// Parameters of the gated stack, shapes for C channels, L layers, D components:
struct WaveNetStackWeights {
  torch::Tensor in_weight;    // [C]          input projection of the 1 input channel
  torch::Tensor in_bias;      // [C]
  torch::Tensor gate_weight;  // [L, 2C, 2C]  rows: filter | gate; columns: tap k | tap k - d
  torch::Tensor gate_bias;    // [L, P, 2C]   P = D (per-component bias) or 1 (shared)
  torch::Tensor out_weight;   // [L, 2C, C]   rows: residual | skip
  torch::Tensor out_bias;     // [L, 2C]
  std::vector<int64_t> dilations;  // L values, each in [1, D)
};

// True when the fused kernel can run these tensors (contiguous float32 on the CPU).
bool wavenet_kernel_supports(const torch::Tensor& inputs);

// inputs [N, D]: the input channel per component (the target shifted right by one).
// cond [N, L, 2C]: the per-layer projection of the global conditioning (broadcast over D).
// Returns the skip sum S [N, D, C] = sum over layers of O[:, C:] (with biases).
// Differentiable w.r.t. cond and all weights; no gradient flows to `inputs` (data).
torch::Tensor wavenet_stack_kernel(const torch::Tensor& inputs, const torch::Tensor& cond,
                                   const WaveNetStackWeights& weights);

// Positions per chunk; 0 restores the default. For benchmarks and tests of chunk borders.
void set_wavenet_chunk_positions(int64_t positions);
int64_t wavenet_chunk_positions(int64_t state_dim);

}  // namespace vaegail::vae
