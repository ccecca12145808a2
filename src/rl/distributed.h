// Batches spread over the processes of a run (util/world.h), and the sums that make K ranks
// compute what one process with all the environments would.
//
// A run's environments have global indices 0..E-1; a rank steps the slice [first, first + N)
// (EnvSlice). A rollout of T steps is flattened time-major, so the run's batch row of
// (step t, environment e) is t·E + e whatever the slicing; a rank holds the rows of its
// environments (RowSlice). Everything random that touches rows (minibatch shuffles, the
// Fisher subsample, the discriminator's demonstration draws) is drawn over the global rows, and
// every mean is a sum over the rank's rows divided by the global count, summed over ranks.
// With one process these reduce to the plain computations.
#pragma once

#include <torch/torch.h>

#include <cstdint>
#include <vector>

namespace vaegail {

// This rank's environments (or rows of a batch): global indices [first, first + count) of `total`.
struct EnvSlice {
  int first = 0;
  int count = 0;
  int total = 0;
  // The slice of `total` environments that this process of the run's world steps (total must
  // be a multiple of the world's size: std::invalid_argument otherwise).
  static EnvSlice of_world(int total);
  static EnvSlice whole(int total) { return {0, total, total}; }
  // Rank `rank` of `ranks`'s share of `total` rows that need not divide evenly (the VAE's
  // minibatches, whose last one is short): [rank·total/ranks, (rank+1)·total/ranks), contiguous
  // and in rank order, the counts differing by at most one (a rank holds none when total < ranks).
  static EnvSlice share(int total, int rank, int ranks);
};

// This rank's rows of a batch of `global_size` rows: global_rows [B] (long, CPU) gives each
// local row's global index.
struct RowSlice {
  torch::Tensor global_rows;
  std::int64_t global_size = 0;

  static RowSlice whole(std::int64_t size);
  // The rows of a time-major [T, slice.count] block of a [T, slice.total] rollout.
  static RowSlice of_rollout(std::int64_t steps, const EnvSlice& slice);
  std::int64_t size() const { return global_rows.size(0); }
  // Which local rows hold `global` (a subset of the global rows, in its order), as local
  // indices in that order; rows held by other ranks are skipped.
  torch::Tensor local_rows(const torch::Tensor& global) const;
};

// Summed over the ranks (a copy; the identity in a world of one). Any dtype castable to double.
torch::Tensor all_sum(const torch::Tensor& t);
double all_sum(double value);
// After backward(): every parameter's gradient becomes the sum of the ranks' gradients (one
// message for all of them). Parameters without a gradient count as zero.
void all_sum_gradients(const std::vector<torch::Tensor>& parameters);

}  // namespace vaegail
