#include "gail/behavior_cloning.h"

#include <chrono>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "gail/gail_demos.h"
#include "gail/run_dir.h"
#include "util/checkpoint_file.h"
#include "util/csv_log.h"
#include "util/rng.h"
#include "util/run_lock.h"
#include "vae/demo_dataset.h"

namespace vaegail {

namespace fs = std::filesystem;

BehaviorCloning::BehaviorCloning(const torch::Tensor& observations, const torch::Tensor& actions,
                                 BcOptions options)
    : options_(std::move(options)) {
  if (observations.size(0) != actions.size(0) || observations.size(0) == 0)
    throw std::invalid_argument("BehaviorCloning: needs as many (non-zero) observations as actions");
  if (options_.batch_size < 1) throw std::invalid_argument("BehaviorCloning: batch_size must be positive");
  agent_ = make_bc_agent(options_, observations, static_cast<int>(actions.size(1)));
  observations_ = observations.to(agent_->device(), torch::kFloat32);
  actions_ = actions.to(agent_->device(), torch::kFloat32);
  optimizer_ = std::make_unique<torch::optim::Adam>(agent_->policy().parameters(),
                                                    torch::optim::AdamOptions(options_.learning_rate));
}

torch::Tensor BehaviorCloning::negative_log_likelihood(const torch::Tensor& observations,
                                                       const torch::Tensor& actions) {
  const auto none = torch::zeros({observations.size(0), 0});
  return -agent_->policy().distribution(agent_->input(observations, none)).log_prob(actions).mean();
}

double BehaviorCloning::train_epoch() {
  auto generator = at::detail::createCPUGenerator(derive_seed(options_.seed, static_cast<std::uint64_t>(epoch_) + 1));
  const auto order = torch::randperm(observations_.size(0), generator, torch::kLong).to(observations_.device());
  double total = 0;
  int64_t seen = 0;
  for (const auto& batch : order.split(options_.batch_size)) {
    const auto loss = negative_log_likelihood(observations_.index_select(0, batch), actions_.index_select(0, batch));
    optimizer_->zero_grad();
    loss.backward();
    optimizer_->step();
    total += loss.item<double>() * static_cast<double>(batch.size(0));
    seen += batch.size(0);
  }
  ++epoch_;
  return total / static_cast<double>(seen);
}

double BehaviorCloning::nll(const torch::Tensor& observations, const torch::Tensor& actions) {
  torch::NoGradGuard no_grad;
  return negative_log_likelihood(observations.to(agent_->device()), actions.to(agent_->device())).item<double>();
}

void BehaviorCloning::save_checkpoint(const std::string& path) const {
  torch::serialize::OutputArchive root, agent, optimizer;
  agent_->save(agent);
  optimizer_->save(optimizer);
  root.write("agent", agent);
  root.write("optimizer", optimizer);
  root.write("epoch", torch::tensor(static_cast<int64_t>(epoch_)));
  write_checkpoint(path, [&](std::ostream& out) { root.save_to(out); });
}

void BehaviorCloning::load_checkpoint(const std::string& path) {
  torch::serialize::InputArchive root, agent, optimizer;
  root.load_from(path, agent_->device());
  root.read("agent", agent);
  root.read("optimizer", optimizer);
  agent_->load(agent);
  optimizer_->load(optimizer);
  torch::Tensor epoch;
  root.read("epoch", epoch);
  epoch_ = static_cast<int>(epoch.item<int64_t>());
}

void train_bc(const DemoSet& demos, const BcOptions& options, const std::string& run_dir,
              const std::function<void(const BcEpoch&)>& on_epoch) {
  const RunLock lock = lock_run_directory(run_dir);
  fs::create_directories(run_dir + "/checkpoints");
  check_or_write_config(run_dir + "/config.json", options, {"epochs", "device"});
  const auto split = vae::split_demos(demos, options.seed);
  const GailDemos train = make_gail_demos(demos, split.train, nullptr);
  BehaviorCloning bc(train.observations, train.actions, options);
  const std::string checkpoint = run_dir + "/checkpoints/latest.pt", metrics = run_dir + "/metrics.csv";
  if (fs::exists(checkpoint)) bc.load_checkpoint(checkpoint);
  truncate_metrics(metrics, bc.epoch());
  CsvLog log(metrics, {"epoch", "train_nll", "val_nll", "seconds"});
  torch::Tensor val_obs, val_act;
  if (!split.val.empty()) {
    const GailDemos val = make_gail_demos(demos, split.val, nullptr);
    val_obs = val.observations;
    val_act = val.actions;
  }
  const auto start = std::chrono::steady_clock::now();
  while (bc.epoch() < options.epochs) {
    BcEpoch e;
    e.train_nll = bc.train_epoch();
    e.epoch = bc.epoch();
    e.val_nll = val_obs.defined() ? bc.nll(val_obs, val_act) : std::numeric_limits<double>::quiet_NaN();
    e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    log.write({{"epoch", e.epoch}, {"train_nll", e.train_nll}, {"val_nll", e.val_nll}, {"seconds", e.seconds}});
    bc.save_checkpoint(checkpoint);
    if (on_epoch) on_epoch(e);
  }
}

}  // namespace vaegail
