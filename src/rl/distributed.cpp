#include "rl/distributed.h"

#include <stdexcept>
#include <string>

#include "util/world.h"

namespace vaegail {

EnvSlice EnvSlice::of_world(int total) {
  const World& world = World::get();
  if (total < world.size() || total % world.size() != 0)
    throw std::invalid_argument("the run's " + std::to_string(total) + " environments cannot be shared equally by " +
                                std::to_string(world.size()) + " ranks");
  const int count = total / world.size();
  return {world.rank() * count, count, total};
}

EnvSlice EnvSlice::share(int total, int rank, int ranks) {
  if (total < 0 || ranks < 1 || rank < 0 || rank >= ranks)
    throw std::invalid_argument("EnvSlice::share: rank " + std::to_string(rank) + " of " + std::to_string(ranks) +
                                " ranks cannot hold a share of " + std::to_string(total) + " rows");
  const auto bound = [&](int r) { return static_cast<int>(static_cast<std::int64_t>(r) * total / ranks); };
  return {bound(rank), bound(rank + 1) - bound(rank), total};
}

RowSlice RowSlice::whole(std::int64_t size) { return {torch::arange(size, torch::kLong), size}; }

RowSlice RowSlice::of_rollout(std::int64_t steps, const EnvSlice& slice) {
  const auto t = torch::arange(steps, torch::kLong).unsqueeze(1);
  const auto e = torch::arange(slice.first, slice.first + slice.count, torch::kLong).unsqueeze(0);
  return {(t * slice.total + e).reshape({-1}), steps * slice.total};
}

torch::Tensor RowSlice::local_rows(const torch::Tensor& global) const {
  const auto g = global.to(torch::kCPU, torch::kLong);
  if (size() == global_size) {
    // Every row is here; global_rows is then the identity in every use of this file.
    return g;
  }
  auto local_of_global = torch::full({global_size}, -1, torch::kLong);
  local_of_global.index_put_({global_rows}, torch::arange(size(), torch::kLong));
  const auto local = local_of_global.index_select(0, g);
  return local.masked_select(local >= 0);
}

torch::Tensor all_sum(const torch::Tensor& t) {
  const World& world = World::get();
  if (!world.distributed()) return t;
  auto buffer = t.detach().to(torch::kCPU, torch::kFloat64).contiguous().clone();
  world.sum(buffer.data_ptr<double>(), buffer.numel());
  return buffer.to(t.device(), t.scalar_type());
}

double all_sum(double value) { return World::get().sum(value); }

void all_sum_gradients(const std::vector<torch::Tensor>& parameters) {
  const World& world = World::get();
  if (!world.distributed()) return;
  std::vector<torch::Tensor> flat;
  for (const auto& p : parameters)
    flat.push_back(p.grad().defined() ? p.grad().reshape({-1}) : torch::zeros({p.numel()}, p.options()));
  const auto summed = all_sum(torch::cat(flat));
  int64_t offset = 0;
  torch::NoGradGuard no_grad;
  for (const auto& p : parameters) {
    auto part = summed.slice(0, offset, offset + p.numel()).view_as(p);
    if (p.grad().defined())
      p.mutable_grad().copy_(part);
    else
      p.mutable_grad() = part.clone();
    offset += p.numel();
  }
}

}  // namespace vaegail
