// Running observation statistics, so that bodies whose observations span very different
// scales (joint angles vs. velocities) feed the networks values of order one.
//
// The statistics are torch buffers (float64): they travel with the module to a device and
// into a checkpoint together with the policy that was trained on them.
#pragma once

#include <torch/torch.h>

namespace vaegail {

class ObsNormalizer : public torch::nn::Module {
 public:
  // clip bounds the normalised values to [-clip, clip]: a rare outlier state cannot saturate
  // the networks.
  explicit ObsNormalizer(int dim, double clip = 10.0);

  int dim() const { return dim_; }
  // Merges the moments of batch [B, dim] into the running ones (Chan et al.'s parallel
  // Welford update), unless frozen.
  void update(const torch::Tensor& batch);
  // update() with the run's batch when each rank holds a share of it (rl/distributed.h): the
  // moments of all ranks' rows, so every rank's statistics stay equal.
  void update_over_ranks(const torch::Tensor& rank_batch);
  // [..., dim] → same shape and dtype: (x - mean) / sqrt(var + eps), clipped.
  torch::Tensor normalize(const torch::Tensor& x) const;

  // A frozen normaliser ignores update(): evaluation must not shift the statistics a policy
  // was trained with.
  void set_frozen(bool frozen) { frozen_ = frozen; }

  const torch::Tensor& mean() const { return mean_; }
  const torch::Tensor& var() const { return var_; }
  double count() const { return count_.item<double>(); }

 private:
  // Chan et al.'s merge of a batch's moments (population variance) into the running ones.
  void merge(const torch::Tensor& batch_mean, const torch::Tensor& batch_var, double batch_count);

  int dim_;
  double clip_;
  bool frozen_ = false;
  torch::Tensor mean_, var_, count_;
};

}  // namespace vaegail
