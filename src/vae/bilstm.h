// The encoder's recurrent part: a bidirectional LSTM of L layers over batch-first sequences whose
// real steps are a prefix of each row. Same maths, parameter names, shapes and initialisation as
// torch::nn::LSTM(LSTMOptions(input, hidden).num_layers(L).bidirectional(true).batch_first(true))
// run on packed sequences, so checkpoints written with the stock module load unchanged.
//
// Why not the stock module: on a CPU its autograd records a dozen small ops per step and layer
// direction, and its backward replays them one by one. Here each layer direction projects the
// inputs of all its steps in one GEMM; the recurrence is one [B, H] x [H, 4H] GEMM and one fused
// cell per step, and its backward through time is written by hand (lstm_recurrence), so autograd
// sees a handful of nodes per layer.
#pragma once

#include <torch/torch.h>

#include <array>
#include <vector>

namespace vaegail::vae {

class BiLstmImpl : public torch::nn::Module {
 public:
  BiLstmImpl(int64_t input_size, int64_t hidden, int64_t layers);

  // x [B, S, D]; lengths [B] (int64, CPU; row b's real steps are its first lengths[b], 1 <= lengths[b]
  // <= S) -> [B, S, 2H]: per step the forward then the backward direction's hidden state of the last
  // layer, zero at padded steps. Padded inputs are never read; the backward direction of a row starts
  // at its last real step.
  torch::Tensor forward(const torch::Tensor& x, const torch::Tensor& lengths);

 private:
  struct Direction {
    torch::Tensor w_ih, w_hh, b_ih, b_hh;  // [4H, in], [4H, H], [4H], [4H]; gates in order i, f, g, o
  };
  std::vector<std::array<Direction, 2>> layers_;  // [layer][0 = forward, 1 = backward]
};
TORCH_MODULE(BiLstm);

// The hidden states of one LSTM direction from its input projections, time-major, h_0 = c_0 = 0:
// gates_in [S, B, 4H] = x_t W_ih^T + b_ih + b_hh (gates i, f, g, o), w_hh [4H, H] -> h [S, B, H].
// Differentiable in both arguments, with a hand-written backward through time.
torch::Tensor lstm_recurrence(const torch::Tensor& gates_in, const torch::Tensor& w_hh);

}  // namespace vaegail::vae
