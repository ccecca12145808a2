#include "vae/vae_trainer.h"

#include <ATen/CPUGeneratorImpl.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <stdexcept>

#include "rl/distributed.h"
#include "util/atomic_file.h"
#include "util/checkpoint_file.h"
#include "util/csv_log.h"
#include "util/progress.h"
#include "util/rng.h"
#include "util/malloc_tuning.h"
#include "util/world.h"

namespace vaegail::vae {

namespace {

// Random streams, each derived from (seed, stream) and then per epoch / batch.
enum Stream : uint64_t { kInit = 1, kShuffle = 2, kNoise = 3, kEval = 4, kEncoderNoise = 5 };

uint64_t stream_seed(uint64_t seed, Stream stream, uint64_t a, uint64_t b = 0) {
  return derive_seed(derive_seed(derive_seed(seed, stream), a), b);
}

// N(0, I) noise of a whole batch, [rows.total, dims...], drawn from `seed`; this rank's rows of it.
// Drawn whole and sliced, so that a row's noise does not depend on how many ranks share the batch.
torch::Tensor standard_normal(const EnvSlice& rows, std::vector<int64_t> dims, uint64_t seed,
                              const torch::Device& device) {
  auto gen = at::detail::createCPUGenerator(seed);
  dims.insert(dims.begin(), rows.total);
  return at::randn(dims, gen, torch::TensorOptions(torch::kFloat)).narrow(0, rows.first, rows.count).to(device);
}

// This rank's share of a batch of n rows (all of them in a world of one).
EnvSlice rank_share(int64_t n) {
  const World& world = World::get();
  return EnvSlice::share(static_cast<int>(n), world.rank(), world.size());
}

// metrics.csv's columns, in the order existing files have them.
const std::vector<std::string> kMetricColumns = {"epoch",          "train_loss",    "train_action_nll",
                                                 "train_state_nll", "train_kl",      "val_loss",
                                                 "val_action_nll",  "val_state_nll", "val_kl",
                                                 "seconds"};

// The loss terms of one split as metrics.csv names them (train_loss, train_action_nll, ...).
void add_loss_terms(Metrics& row, const std::string& split, const LossTerms& t) {
  row[split + "_loss"] = t.total;
  row[split + "_action_nll"] = t.action_nll;
  row[split + "_state_nll"] = t.state_nll;
  row[split + "_kl"] = t.kl;
}

void accumulate(LossTerms& sum, const VaeLoss& loss, double weight) {
  sum.total += weight * loss.total.item<double>();
  sum.action_nll += weight * loss.action_nll.item<double>();
  sum.state_nll += weight * loss.state_nll.item<double>();
  sum.kl += weight * loss.kl.item<double>();
}

// Sums over this rank's rows become sums over the run's.
LossTerms summed_over_ranks(LossTerms t) {
  double values[] = {t.total, t.action_nll, t.state_nll, t.kl};
  World::get().sum(values, 4);
  return {values[0], values[1], values[2], values[3]};
}

LossTerms added(LossTerms a, const LossTerms& b) {
  a.total += b.total;
  a.action_nll += b.action_nll;
  a.state_nll += b.state_nll;
  a.kl += b.kl;
  return a;
}

LossTerms scaled(LossTerms t, double factor) {
  t.total *= factor;
  t.action_nll *= factor;
  t.state_nll *= factor;
  t.kl *= factor;
  return t;
}

}  // namespace

double scheduled_learning_rate(const VaeConfig& config, int epoch) {
  if (epoch < 1) throw std::invalid_argument("scheduled_learning_rate: epochs count from 1");
  const int E = config.lr_decay_epochs;
  if (E == 0) return config.learning_rate;
  if (epoch > E)
    throw std::invalid_argument("epoch " + std::to_string(epoch) + " runs past lr_decay_epochs (" +
                                std::to_string(E) + "), where the learning rate is 0");
  return config.learning_rate * 0.5 * (1.0 + std::cos(M_PI * (epoch - 1) / E));
}

TrajectoryDataset TrajectoryDataset::select(const torch::Tensor& index,
                                            const torch::Device& device) const {
  const auto i = index.to(states.device());
  return {states.index_select(0, i).to(device), actions.index_select(0, i).to(device),
          mask.defined() ? mask.index_select(0, i).to(device) : torch::Tensor()};
}

void TrajectoryDataset::validate(const VaeConfig& c) const {
  auto fail = [](const std::string& why) { throw std::invalid_argument("dataset: " + why); };
  if (!states.defined() || !actions.defined()) fail("states and actions are required");
  if (states.dim() != 3 || states.size(2) != c.state_dim)
    fail("states must be [M, T+1, " + std::to_string(c.state_dim) + "]");
  if (actions.dim() != 3 || actions.size(2) != c.action_dim)
    fail("actions must be [M, T, " + std::to_string(c.action_dim) + "]");
  if (actions.size(0) != states.size(0) || states.size(1) != actions.size(1) + 1)
    fail("states [M, T+1, D] and actions [M, T, A] disagree on M or T");
  if (mask.defined() && (mask.dim() != 2 || mask.size(0) != actions.size(0) ||
                         mask.size(1) != actions.size(1)))
    fail("mask must be [M, T]");
  if (mask.defined()) mask_lengths(mask);  // prefix rows, none empty
}

VaeTrainer::VaeTrainer(const VaeConfig& config, TrainerOptions options, TrajectoryDataset train,
                       TrajectoryDataset val)
    : config_(config), options_(std::move(options)), train_(std::move(train)),
      val_(std::move(val)) {
  retain_freed_memory();
  config_.validate();
  if (options_.run_dir.empty()) throw std::invalid_argument("VaeTrainer: run_dir is required");
  train_.validate(config_);
  if (train_.size() == 0) throw std::invalid_argument("VaeTrainer: empty training set");
  if (val_.size() > 0) val_.validate(config_);
  if (options_.epochs >= 1) scheduled_learning_rate(config_, options_.epochs);  // the run fits the schedule

  torch::manual_seed(stream_seed(options_.seed, kInit, 0));
  model_ = TrajectoryVae(config_);
  model_->fit_normalization(train_.states, train_.actions, train_.mask);
  model_->to(options_.device);
  optimizer_ = std::make_unique<torch::optim::Adam>(
      model_->parameters(),
      torch::optim::AdamOptions(config_.learning_rate).weight_decay(config_.weight_decay));

  // Under mpirun every rank holds the whole model and data set (the same split, normalisation
  // and initialisation: all seeded) and trains its share of each batch; rank 0 alone writes.
  const World& world = World::get();
  lock_ = lock_run_directory(options_.run_dir);  // rank 0's: the ranks are one writer
  if (world.is_root())
    std::filesystem::create_directories(std::filesystem::path(options_.run_dir) / "checkpoints");
  // Every rank has read its command's files (`vae train` reads run_dir/config.json when
  // resuming) before rank 0 writes any.
  world.barrier();
  if (std::filesystem::exists(checkpoint_path()))
    load_checkpoint(checkpoint_path());  // every rank
  else if (std::filesystem::exists(weights_path()))
    resume_from_weights();
  if (world.is_root()) {
    truncate_metrics(metrics_path(), epoch_);  // rows past the checkpoint: the resumed run redoes them
    config_.save((std::filesystem::path(options_.run_dir) / "config.json").string());
  }
}

std::string VaeTrainer::checkpoint_path() const { return checkpoint_file("latest.pt"); }

std::string VaeTrainer::weights_path() const {
  return (std::filesystem::path(options_.run_dir) / kWeightsFile).string();
}

void VaeTrainer::resume_from_weights() {
  const std::string path = weights_path();
  read_checkpoint(path, [&](const std::string& file) {
    torch::serialize::InputArchive archive, model_archive;
    archive.load_from(file, options_.device);
    c10::IValue config_json, epoch;
    archive.read("config", config_json);
    if (VaeConfig::from_json(config_json.toStringRef()) != config_)
      throw std::invalid_argument(path + ": weights of a VAE with a different VaeConfig");
    if (!archive.try_read("epoch", epoch))
      throw std::invalid_argument(path + ": an exported weights file (no epoch): resume needs the trainer's own");
    archive.read("model", model_archive);
    model_->load(model_archive);
    epoch_ = static_cast<int>(epoch.toInt());
  });
  warmup_epoch_ = epoch_ + 1;
  if (World::get().is_root())
    std::fprintf(stderr, "vaegail: note: %s: resumed from the weights alone at epoch %d (Adam's moments start afresh: the rate ramps up over epoch %d)\n",
                 path.c_str(), epoch_, warmup_epoch_);
}

double VaeTrainer::batch_learning_rate(int epoch, int64_t batch) const {
  const double lr = scheduled_learning_rate(config_, epoch);
  if (epoch != warmup_epoch_) return lr;
  const int64_t batches = (train_.size() + config_.batch_size - 1) / config_.batch_size;
  return lr * static_cast<double>(batch + 1) / static_cast<double>(batches);
}

std::string VaeTrainer::epoch_checkpoint_path(int epoch) const {
  return checkpoint_file("epoch_" + std::to_string(epoch) + ".pt");
}

std::string VaeTrainer::checkpoint_file(const std::string& name) const {
  return (std::filesystem::path(options_.run_dir) / "checkpoints" / name).string();
}

std::string VaeTrainer::metrics_path() const {
  return (std::filesystem::path(options_.run_dir) / "metrics.csv").string();
}

std::vector<EpochMetrics> VaeTrainer::train() {
  std::vector<EpochMetrics> out;
  while (epoch_ < options_.epochs) out.push_back(train_epoch());
  return out;
}

EpochMetrics VaeTrainer::train_epoch() {
  const auto start = std::chrono::steady_clock::now();
  const int e = epoch_ + 1;
  const int64_t M = train_.size(), bs = config_.batch_size;

  // Fisher-Yates with this epoch's stream.
  std::vector<int64_t> order(M);
  for (int64_t i = 0; i < M; ++i) order[i] = i;
  Rng rng(stream_seed(options_.seed, kShuffle, e));
  for (int64_t i = M - 1; i > 0; --i)
    std::swap(order[i], order[rng.next() % static_cast<uint64_t>(i + 1)]);
  const auto perm = torch::tensor(order, torch::kLong);

  std::unique_ptr<Progress> progress;
  const int64_t batches = (M + bs - 1) / bs;
  if (options_.progress)
    progress = std::make_unique<Progress>(
        "vae epoch " + std::to_string(e) + "/" + std::to_string(options_.epochs), batches, "batch");

  model_->train();
  const auto parameters = model_->parameters();
  LossTerms sum;
  for (int64_t b = 0; b < batches; ++b) {
    const int64_t n = std::min(bs, M - b * bs);
    // This rank's rows of the batch; the batch's mean loss is the sum over every rank's rows / n.
    const EnvSlice rows = rank_share(n);
    const double lr = batch_learning_rate(e, b);
    for (auto& group : optimizer_->param_groups())
      static_cast<torch::optim::AdamOptions&>(group.options()).lr(lr);
    optimizer_->zero_grad();
    LossTerms batch_sum;  // over this rank's rows
    if (rows.count > 0) {
      const auto batch = train_.select(perm.narrow(0, b * bs + rows.first, rows.count), options_.device);
      const auto noise =
          standard_normal(rows, {config_.latent_dim}, stream_seed(options_.seed, kNoise, e, b), options_.device);
      const auto encoder_noise =
          config_.encoder_input_noise > 0
              ? standard_normal(rows, {train_.states.size(1), config_.state_dim},
                                stream_seed(options_.seed, kEncoderNoise, e, b), options_.device)
              : torch::Tensor();
      const auto loss = model_->loss(batch.states, batch.actions, batch.mask, noise, encoder_noise);
      (loss.total * (static_cast<double>(rows.count) / static_cast<double>(n))).backward();
      accumulate(batch_sum, loss, static_cast<double>(rows.count));
    }
    all_sum_gradients(parameters);  // every rank then takes the same Adam step
    optimizer_->step();
    batch_sum = summed_over_ranks(batch_sum);
    sum = added(sum, batch_sum);
    if (progress) {
      progress->set_status(fmt::format("loss {:.4g}", batch_sum.total / static_cast<double>(n)));
      progress->advance();
    }
  }
  if (progress) progress->finish();
  epoch_ = e;

  EpochMetrics m;
  m.epoch = e;
  m.train = scaled(sum, 1.0 / static_cast<double>(M));
  m.train_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double nan = std::nan("");
  m.val = val_.size() > 0 ? evaluate(val_) : LossTerms{nan, nan, nan, nan};
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // The row first, then the checkpoint: a run killed between the two redoes the epoch on
  // resume (reproducibly) and replaces the row, rather than losing it.
  if (World::get().is_root()) {
    Metrics row = {{"epoch", e}, {"seconds", m.seconds}};
    add_loss_terms(row, "train", m.train);
    add_loss_terms(row, "val", m.val);
    CsvLog(metrics_path(), kMetricColumns).write(row);
    save_checkpoint(checkpoint_path());
    save_vae_weights(model_, weights_path(), epoch_);
    if (options_.keep_epochs) save_checkpoint(epoch_checkpoint_path(e));
  }
  return m;
}

LossTerms VaeTrainer::evaluate(const TrajectoryDataset& data) {
  torch::NoGradGuard no_grad;
  model_->eval();
  const int64_t M = data.size(), bs = std::max(1, options_.eval_batch_size);
  LossTerms sum;  // over this rank's rows of every batch
  for (int64_t b = 0; b * bs < M; ++b) {
    const EnvSlice rows = rank_share(std::min(bs, M - b * bs));
    if (rows.count == 0) continue;
    const auto batch = data.select(torch::arange(b * bs + rows.first, b * bs + rows.first + rows.count), options_.device);
    const auto noise =
        standard_normal(rows, {config_.latent_dim}, stream_seed(options_.seed, kEval, epoch_, b), options_.device);
    accumulate(sum, model_->loss(batch.states, batch.actions, batch.mask, noise),
               static_cast<double>(rows.count));
  }
  model_->train();
  return scaled(summed_over_ranks(sum), 1.0 / static_cast<double>(std::max<int64_t>(1, M)));
}

void VaeTrainer::save_checkpoint(const std::string& path) {
  torch::serialize::OutputArchive archive, model_archive, optimizer_archive;
  model_->save(model_archive);
  optimizer_->save(optimizer_archive);
  archive.write("model", model_archive);
  archive.write("optimizer", optimizer_archive);
  archive.write("epoch", c10::IValue(static_cast<int64_t>(epoch_)));
  archive.write("seed", c10::IValue(static_cast<int64_t>(options_.seed)));
  archive.write("config", c10::IValue(config_.to_json()));
  write_checkpoint(path, [&](std::ostream& out) { archive.save_to(out); });
}

void VaeTrainer::load_checkpoint(const std::string& path) {
  torch::serialize::InputArchive archive, model_archive, optimizer_archive;
  archive.load_from(path, options_.device);
  c10::IValue config_json, epoch, seed;
  archive.read("config", config_json);
  if (VaeConfig::from_json(config_json.toStringRef()) != config_)
    throw std::invalid_argument(path + ": checkpoint was trained with a different VaeConfig");
  archive.read("seed", seed);
  if (static_cast<uint64_t>(seed.toInt()) != options_.seed)
    throw std::invalid_argument(path + ": checkpoint was trained with seed " +
                                std::to_string(static_cast<uint64_t>(seed.toInt())));
  archive.read("model", model_archive);
  archive.read("optimizer", optimizer_archive);
  archive.read("epoch", epoch);
  model_->load(model_archive);
  optimizer_->load(optimizer_archive);
  epoch_ = static_cast<int>(epoch.toInt());
}

std::pair<torch::Tensor, torch::Tensor> encode(TrajectoryVae& model, const TrajectoryDataset& data,
                                               int64_t batch_size) {
  return encode(model, data.states, data.mask, batch_size);
}

}  // namespace vaegail::vae
