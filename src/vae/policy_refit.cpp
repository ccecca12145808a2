#include "vae/policy_refit.h"

#include <ATen/CPUGeneratorImpl.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "util/checkpoint_file.h"
#include "util/csv_log.h"
#include "util/progress.h"
#include "util/run_lock.h"
#include "util/rng.h"
#include "vae/gaussian.h"

namespace vaegail::vae {

namespace fs = std::filesystem;

StepRecords step_records(TrajectoryVae& model, const TrajectoryDataset& data, const torch::Tensor& mu) {
  torch::NoGradGuard no_grad;
  const int64_t M = data.size();
  if (M == 0) return {};
  if (mu.dim() != 2 || mu.size(0) != M)
    throw std::invalid_argument("step_records: mu must be [" + std::to_string(M) + ", Z]");
  const int64_t T = data.actions.size(1), D = data.states.size(2), A = data.actions.size(2), Z = mu.size(1);
  const auto x = model->policy_input(model->normalize_states(data.states.narrow(1, 0, T))).reshape({M * T, D});
  const auto a = model->normalize_actions(model->modelled_actions(data.states, data.actions)).reshape({M * T, A});
  const auto z = mu.to(x.scalar_type()).unsqueeze(1).expand({M, T, Z}).reshape({M * T, Z});
  if (!data.mask.defined()) return {x.contiguous(), z.contiguous(), a.contiguous()};
  const auto real = data.mask.to(torch::kBool).reshape({M * T}).nonzero().squeeze(1);
  return {x.index_select(0, real), z.index_select(0, real), a.index_select(0, real)};
}

torch::Tensor latents_by_label(const torch::Tensor& source_mu, const std::vector<double>& source_labels,
                               const std::vector<double>& target_labels, std::uint64_t seed) {
  if (source_mu.dim() != 2 || source_mu.size(0) != static_cast<int64_t>(source_labels.size()))
    throw std::invalid_argument("latents_by_label: source_mu must be [" + std::to_string(source_labels.size()) + ", Z]");
  std::map<double, std::vector<int64_t>> rows;
  for (size_t j = 0; j < source_labels.size(); ++j) rows[source_labels[j]].push_back(static_cast<int64_t>(j));
  Rng rng(seed);
  std::vector<int64_t> chosen;
  for (double label : target_labels) {
    const auto it = rows.find(label);
    if (it == rows.end()) throw std::invalid_argument(fmt::format("no source demonstration has the label {}", label));
    chosen.push_back(it->second[rng.next() % it->second.size()]);
  }
  return source_mu.index_select(0, torch::tensor(chosen, torch::kLong));
}

PolicyFit policy_fit(TrajectoryVae& model, const StepRecords& records, int64_t batch) {
  torch::NoGradGuard no_grad;
  const int64_t N = records.size();
  if (N == 0) return {std::nan(""), std::nan("")};
  const auto action_std = model->named_buffers()["action_std"];
  double nll = 0, squared = 0;
  for (int64_t b = 0; b < N; b += batch) {
    const int64_t n = std::min(batch, N - b);
    const auto x = records.x.narrow(0, b, n), z = records.z.narrow(0, b, n), a = records.a.narrow(0, b, n);
    const auto d = model->action_decoder()->forward(x, z);  // one pass for both figures
    nll -= gaussian_log_prob(a, d.mean, d.log_std).sum().item<double>();
    squared += ((d.mean - a) * action_std).square().sum().item<double>();
  }
  return {nll / static_cast<double>(N), std::sqrt(squared / static_cast<double>(N * records.a.size(1)))};
}

namespace {

const std::vector<std::string> kColumns = {"epoch", "learning_rate", "train_action_nll", "train_rmse",
                                           "val_action_nll", "val_rmse", "seconds"};

double cosine_rate(const PolicyRefitOptions& o, int epoch) {
  const double floor = o.learning_rate / 100;
  return floor + (o.learning_rate - floor) * 0.5 * (1 + std::cos(M_PI * (epoch - 1) / std::max(1, o.epochs)));
}

void save_state(TrajectoryVae& model, torch::optim::Adam& adam, int epoch, const std::string& path) {
  torch::serialize::OutputArchive archive, model_archive, optimizer_archive;
  model->save(model_archive);
  adam.save(optimizer_archive);
  archive.write("kind", c10::IValue("vae"));
  archive.write("config", c10::IValue(model->config().to_json()));
  archive.write("model", model_archive);
  archive.write("optimizer", optimizer_archive);
  archive.write("refit_epoch", c10::IValue(static_cast<int64_t>(epoch)));
  rotate_and_write(path, [&](std::ostream& out) { archive.save_to(out); });
}

// The epoch of the state loaded into model and adam, 0 when out_dir has none.
int resume_state(TrajectoryVae& model, torch::optim::Adam& adam, const std::string& path) {
  int epoch = 0;
  const auto resumed = resume_checkpoint(path, [&](const std::string& file) {
    torch::serialize::InputArchive archive, model_archive, optimizer_archive;
    archive.load_from(file);
    c10::IValue config_json, e;
    archive.read("config", config_json);
    if (VaeConfig::from_json(config_json.toStringRef()) != model->config())
      throw std::logic_error(file + ": a refit of a VAE with another config");
    archive.read("model", model_archive);
    archive.read("optimizer", optimizer_archive);
    archive.read("refit_epoch", e);
    model->load(model_archive);
    adam.load(optimizer_archive);
    epoch = static_cast<int>(e.toInt());
  });
  if (!resumed.path.empty()) std::fprintf(stderr, "vaegail: %s at epoch %d\n", resumed.message().c_str(), epoch);
  return epoch;
}

}  // namespace

PolicyRefitResult refit_policy(TrajectoryVae& model, const StepRecords& train, const StepRecords& val,
                               const PolicyRefitOptions& options) {
  if (options.out_dir.empty()) throw std::invalid_argument("refit_policy: out_dir is required");
  if (train.size() == 0) throw std::invalid_argument("refit_policy: no training steps");
  if (options.epochs < 1 || options.batch < 1 || !(options.learning_rate > 0))
    throw std::invalid_argument("refit_policy: epochs, batch and learning rate must be positive");
  fs::create_directories(fs::path(options.out_dir) / "checkpoints");
  const RunLock lock = lock_run_directory(options.out_dir);  // two refits into one directory would interleave
  const std::string latest = (fs::path(options.out_dir) / "checkpoints" / "latest.pt").string();
  const std::string metrics = (fs::path(options.out_dir) / "metrics.csv").string();

  torch::optim::Adam adam(model->action_decoder()->parameters(), torch::optim::AdamOptions(options.learning_rate));
  const int done = resume_state(model, adam, latest);
  truncate_metrics(metrics, done);
  CsvLog log(metrics, kColumns);

  PolicyRefitResult result;
  result.before_train = policy_fit(model, train);
  result.before_val = policy_fit(model, val);
  result.train = result.before_train;
  result.val = result.before_val;
  const int64_t N = train.size(), batches = (N + options.batch - 1) / options.batch;
  std::optional<Progress> progress;
  if (options.progress) {
    progress.emplace("refit", static_cast<std::int64_t>(options.epochs) * batches, "batches");
    progress->resume(static_cast<std::int64_t>(done) * batches);
  }
  const auto action_std = model->named_buffers()["action_std"];
  model->train();
  for (int epoch = done + 1; epoch <= options.epochs; ++epoch) {
    const auto start = std::chrono::steady_clock::now();
    const double lr = cosine_rate(options, epoch);
    for (auto& group : adam.param_groups()) static_cast<torch::optim::AdamOptions&>(group.options()).lr(lr);
    auto generator = at::detail::createCPUGenerator(derive_seed(options.seed, epoch));
    const auto order = torch::randperm(N, generator, torch::kLong);
    for (int64_t b = 0; b < batches; ++b) {
      const auto rows = order.narrow(0, b * options.batch, std::min(options.batch, N - b * options.batch));
      const auto error = model->action_decoder()->mean(train.x.index_select(0, rows), train.z.index_select(0, rows)) -
                         train.a.index_select(0, rows);
      const auto loss = (error * action_std).square().mean();
      adam.zero_grad();
      loss.backward();
      adam.step();
      if (progress) progress->advance();
    }
    model->eval();
    result.train = policy_fit(model, train);
    result.val = policy_fit(model, val);
    model->train();
    ++result.epochs_run;
    if (progress) progress->set_status(fmt::format("epoch {} val nll {:.2f} rmse {:.4f}", epoch, result.val.nll, result.val.rmse));
    log.write({{"epoch", epoch},
               {"learning_rate", lr},
               {"train_action_nll", result.train.nll},
               {"train_rmse", result.train.rmse},
               {"val_action_nll", result.val.nll},
               {"val_rmse", result.val.rmse},
               {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()}});
    save_state(model, adam, epoch, latest);
    save_vae_weights(model, (fs::path(options.out_dir) / kWeightsFile).string());
  }
  if (progress) progress->finish();
  model->eval();
  return result;
}

}  // namespace vaegail::vae
