// `vaegail vae ...`: train the trajectory VAE on a demonstration file, embed demonstrations,
// test the embedding with k-NN, check that the policy reads z, imitate demonstrations and
// interpolate between them with the VAE policy; and `vaegail bench vae`.
#include <torch/torch.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <iterator>
#include <memory>
#include <stdexcept>

#include "bench/vae_bench.h"
#include "cli/commands.h"
#include "cli/task_options.h"
#include "env/registry.h"
#include "eval/embedding.h"
#include "util/atomic_file.h"
#include "util/checkpoint_file.h"
#include "util/progress.h"
#include "util/world.h"
#include "vae/action_error.h"
#include "vae/demo_dataset.h"
#include "vae/imitation.h"
#include "vae/latent_refinement.h"
#include "vae/policy_refit.h"
#include "vae/vae_trainer.h"

namespace vaegail::cli {

namespace fs = std::filesystem;
using vae::TrajectoryVae;

namespace {

constexpr const char* kDeviceHelp = "cpu, or cuda (the state decoder then runs its conv1d path)";

void require_dims_match(const TrajectoryVae& model, const DemoSet& demos) {
  const auto& c = model->config();
  if (demos.header.obs_dim() != c.state_dim || demos.header.act_dim() != c.action_dim)
    throw std::invalid_argument(demos.path + ": observations/actions have " + std::to_string(demos.header.obs_dim()) +
                                "/" + std::to_string(demos.header.act_dim()) + " components, the checkpoint's VAE " +
                                std::to_string(c.state_dim) + "/" + std::to_string(c.action_dim));
}

std::vector<int64_t> all_episodes(const DemoSet& demos) {
  std::vector<int64_t> index(demos.episodes.size());
  for (size_t i = 0; i < index.size(); ++i) index[i] = static_cast<int64_t>(i);
  return index;
}

// mu (and sigma) of q(z | x) for the episodes, with a progress bar.
torch::Tensor encode_with_progress(TrajectoryVae& model, const DemoSet& demos, const std::vector<int64_t>& episodes,
                                   torch::Tensor* sigma = nullptr) {
  Progress progress("encode", static_cast<std::int64_t>(episodes.size()), "demos");
  auto mu = vae::encode_episodes(model, demos, episodes, sigma, &progress);
  progress.finish();
  return mu;
}

struct ModelFlags {
  std::string checkpoint, demos, device = "cpu";
};

void add_model_flags(CLI::App& command, ModelFlags& f) {
  command.add_option("--checkpoint", f.checkpoint, "VAE run: its directory, checkpoints/latest.pt or weights.pt")->required();
  command.add_option("--demos", f.demos, "demonstration file (.h5)")->required();
  add_device_option(command, f.device, kDeviceHelp);
}

struct Loaded {
  torch::Device device;
  TrajectoryVae model;
  DemoSet demos;
};

Loaded load(const ModelFlags& f) {
  const auto device = parse_device(f.device);
  if (!fs::exists(f.checkpoint)) throw std::invalid_argument(f.checkpoint + ": no such checkpoint");
  Loaded l{device, vae::load_trained_vae(f.checkpoint, device), read_demos(f.demos)};
  l.model->eval();
  require_dims_match(l.model, l.demos);
  return l;
}

// ---- vae train ------------------------------------------------------------------------
struct VaeTrainFlags {
  std::string demos, run_dir, preset = "walker", config, device = "cpu";
  int epochs = 100;
  int batch_size = 0;
  double lr = 0;
  int lr_decay_epochs = -1;
  std::uint64_t seed = 0;
  bool keep_epochs = false;
};

// The run directory's own config when resuming, else the preset; then --config; then flags.
vae::VaeConfig train_config(const VaeTrainFlags& f, const DemoHeader& header) {
  const std::string saved = (fs::path(f.run_dir) / "config.json").string();
  vae::VaeConfig c = fs::exists(saved) ? vae::VaeConfig::load(saved)
                                       : vae::VaeConfig::preset(f.preset, header.obs_dim(), header.act_dim());
  if (!f.config.empty()) c = vae::VaeConfig::load(f.config, c);
  if (f.batch_size > 0) c.batch_size = f.batch_size;
  if (f.lr > 0) c.learning_rate = f.lr;
  if (f.lr_decay_epochs >= 0) c.lr_decay_epochs = f.lr_decay_epochs;
  c.validate();
  return c;
}

void run_vae_train(const VaeTrainFlags& f) {
  auto demos = read_demos(f.demos);
  const auto config = train_config(f, demos.header);
  auto data = vae::make_demo_training_data(std::move(demos), config, f.seed);
  std::printf("%s: %zu training episodes, %zu validation (%s)\n", f.demos.c_str(), data.split.train.size(),
              data.split.val.size(),
              std::any_of(data.demos.episodes.begin(), data.demos.episodes.end(), vae::is_held_out)
                  ? "held-out experts"
                  : "no held-out experts: a seeded 10% of the episodes");
  vae::TrainerOptions options;
  options.run_dir = f.run_dir;
  options.epochs = f.epochs;
  options.seed = f.seed;
  options.device = parse_device(f.device);
  options.keep_epochs = f.keep_epochs;
  vae::VaeTrainer trainer(config, options, data.train, data.val);
  if (World::get().distributed())
    std::printf("%d ranks share each batch of %d trajectories\n", World::get().size(), config.batch_size);
  if (trainer.epoch() > 0) std::printf("resuming %s after epoch %d\n", f.run_dir.c_str(), trainer.epoch());
  while (trainer.epoch() < f.epochs) {
    const auto m = trainer.train_epoch();
    std::printf("epoch %d/%d  train %.2f (action %.2f, state %.2f, kl %.2f)  val %.2f (action %.2f, state %.2f, kl %.2f)  %.1f s\n",
                m.epoch, f.epochs, m.train.total, m.train.action_nll, m.train.state_nll, m.train.kl, m.val.total,
                m.val.action_nll, m.val.state_nll, m.val.kl, m.seconds);
    std::fflush(stdout);
  }
  std::printf("metrics: %s\ncheckpoint: %s\n", trainer.metrics_path().c_str(), trainer.checkpoint_path().c_str());
}

void add_train(CLI::App& vae) {
  auto f = std::make_shared<VaeTrainFlags>();
  CLI::App* c = vae.add_subcommand("train", "train the VAE on demonstrations (rerun with the same --run-dir to resume)");
  c->add_option("--demos", f->demos, "demonstration file (.h5)")->required();
  c->add_option("--run-dir", f->run_dir, "config.json, metrics.csv, checkpoints/latest.pt")->required();
  c->add_option("--preset", f->preset, "network sizes of the paper's Table 1")
      ->check(CLI::IsMember({"walker", "arm", "jaco", "humanoid"}))->capture_default_str();
  c->add_option("--config", f->config, "JSON overriding config fields (see VaeConfig)");
  c->add_option("--epochs", f->epochs, "train until this many epochs in total")->check(CLI::Range(1, 1 << 30))->capture_default_str();
  c->add_option("--batch-size", f->batch_size, "trajectories per step (default: the config's, 32)")->check(CLI::Range(1, 1 << 20));
  c->add_option("--lr", f->lr, "Adam learning rate (default: the config's, 1e-4)")->check(CLI::PositiveNumber);
  c->add_option("--lr-decay-epochs", f->lr_decay_epochs,
                 "cosine decay of the learning rate to 0 over this many epochs (0: constant; default: the config's)")
      ->check(CLI::Range(0, 1 << 30));
  c->add_option("--seed", f->seed, "initialisation, shuffling, noise and the validation split")->capture_default_str();
  c->add_flag("--keep-epochs", f->keep_epochs, "also keep every epoch's checkpoint as checkpoints/epoch_N.pt");
  add_device_option(*c, f->device, kDeviceHelp);
  c->footer(
      "On K cores: mpirun -np K vaegail vae train ... (K processes share each batch and train what one\n"
      "process trains; rank 0 writes the run directory; a run resumes under any K). As root, OpenMPI\n"
      "asks for OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 in the environment.");
  c->callback([f] { run_vae_train(*f); });
}

// ---- vae embed ------------------------------------------------------------------------
struct EmbedFlags : ModelFlags {
  std::string out;
  vae::RefineOptions refine{0, 0.05, 64};
  bool refine_all = false;
};

// The rows whose mu --refine-steps moves: the held-out ones by default, since they are the k-NN
// test's queries, and whether the vote changes when they sit where the decoders explain them best
// says if a miss is the encoder's or the embedding space's. Checked before any encoding.
std::vector<int64_t> rows_to_refine(const DemoSet& demos, const EmbedFlags& f) {
  std::vector<int64_t> rows;
  for (int64_t i = 0; i < static_cast<int64_t>(demos.episodes.size()); ++i)
    if (f.refine_all || vae::is_held_out(demos.episodes[i])) rows.push_back(i);
  if (rows.empty()) throw std::invalid_argument(demos.path + ": no held-out demonstrations to refine (--refine-all?)");
  return rows;
}

// mu with the rows moved towards the mode of p(z | demonstration); sigma stays the encoder's.
torch::Tensor refine_rows(TrajectoryVae& model, const DemoSet& demos, const torch::Tensor& mu,
                          const std::vector<int64_t>& rows, const vae::RefineOptions& refine) {
  const auto index = torch::tensor(rows);
  const auto data = vae::to_trajectory_dataset(demos, rows, model->config());
  const auto refined = vae::refine_with_report(model, data, mu.index_select(0, index), refine);
  std::printf("%zu demonstrations: %s\n", rows.size(), refined.description.c_str());
  return mu.index_copy(0, index, refined.z.to(mu.dtype()));
}

void add_embed(CLI::App& vae) {
  auto f = std::make_shared<EmbedFlags>();
  CLI::App* c = vae.add_subcommand("embed", "one CSV row per demonstration: its labels and q(z | x) = N(mu, sigma)");
  add_model_flags(*c, *f);
  c->add_option("--out", f->out, "CSV: episode,expert_id,context,achieved_speed,held_out,mu_*,sigma_*")->required();
  add_refine_options(*c, f->refine, "the held-out demonstrations' mu");
  c->add_flag("--refine-all", f->refine_all, "with --refine-steps, refine every demonstration's mu");
  c->callback([f] {
    torch::NoGradGuard no_grad;
    auto l = load(*f);
    const auto refined_rows = f->refine.steps > 0 ? rows_to_refine(l.demos, *f) : std::vector<int64_t>{};
    torch::Tensor sigma;
    auto mu = encode_with_progress(l.model, l.demos, all_episodes(l.demos), &sigma);
    if (!refined_rows.empty()) mu = refine_rows(l.model, l.demos, mu, refined_rows, f->refine);
    mu = mu.to(torch::kDouble);
    sigma = sigma.to(torch::kDouble);
    std::vector<eval::EmbeddingRow> rows;
    for (int i = 0; i < static_cast<int>(l.demos.episodes.size()); ++i) {
      const Episode& e = l.demos.episodes[i];
      eval::EmbeddingRow r;
      r.episode = i;
      r.expert_id = e.expert_id;
      r.context = e.context.empty() ? std::nan("") : e.context[0];
      r.achieved_speed = vae::achieved_speed_or_nan(l.demos, i);
      r.held_out = vae::is_held_out(e);
      r.mu.assign(mu[i].data_ptr<double>(), mu[i].data_ptr<double>() + mu.size(1));
      r.sigma.assign(sigma[i].data_ptr<double>(), sigma[i].data_ptr<double>() + sigma.size(1));
      rows.push_back(std::move(r));
    }
    write_file_atomically(f->out, eval::embedding_csv(rows));
    std::printf("%zu embeddings (z %lld) -> %s\n", rows.size(), static_cast<long long>(mu.size(1)), f->out.c_str());
  });
}

// ---- vae knn --------------------------------------------------------------------------
void add_knn(CLI::App& vae) {
  auto path = std::make_shared<std::string>();
  auto k = std::make_shared<int>(5);
  auto leave_one_out = std::make_shared<bool>(false);
  auto by_expert = std::make_shared<bool>(false);
  auto linear = std::make_shared<bool>(false);
  CLI::App* c = vae.add_subcommand(
      "knn", "classify held-out embeddings by the training ones' target: a k-NN vote, or a linear read-out");
  c->add_option("--embeddings", *path, "CSV from `vaegail vae embed`")->required();
  c->add_option("--k", *k, "neighbours")->check(CLI::Range(1, 1 << 20))->capture_default_str();
  c->add_flag("--leave-one-expert-out", *leave_one_out,
              "instead classify every training expert's embeddings against the other training experts'");
  c->add_flag("--by-expert", *by_expert, "also a line per classified expert: its score and its nearest experts");
  c->add_flag("--linear", *linear,
              "instead of the vote, the target as a linear function of mu by ridge regression on the training "
              "rows (the ridge chosen by leaving each training expert out), each row classified as the "
              "training target nearest its read-out (--k unused)");
  c->callback([path, k, leave_one_out, by_expert, linear] {
    const auto rows = eval::parse_embedding_csv(read_file(*path), *path);
    const auto result = *linear ? (*leave_one_out ? eval::linear_classify_leave_one_expert_out(rows)
                                                  : eval::linear_classify(rows))
                                : (*leave_one_out ? eval::knn_classify_leave_one_expert_out(rows, *k)
                                                  : eval::knn_classify(rows, *k));
    std::fputs(eval::format_classification(result, *by_expert).c_str(), stdout);
  });
}

// ---- vae action-error -----------------------------------------------------------------
void print_action_errors(Loaded& l, const std::vector<int64_t>& episodes, const char* label) {
  if (episodes.empty()) return;
  const auto mu = encode_with_progress(l.model, l.demos, episodes);
  const auto data = vae::to_trajectory_dataset(l.demos, episodes, l.model->config());
  for (const auto& row : vae::action_error_by_z_source(l.model, data, mu))
    std::printf("| %s (%zu) | %s | %.3f | %.3f |\n", label, episodes.size(), row.z_source.c_str(),
                row.error.first_step, row.error.later_steps);
}

void add_action_error(CLI::App& vae) {
  auto f = std::make_shared<ModelFlags>();
  CLI::App* c = vae.add_subcommand("action-error", "teacher-forced action error of the VAE policy with the "
                                                   "demonstration's own z, another's and z = 0: does it read z?");
  add_model_flags(*c, *f);
  c->callback([f] {
    torch::NoGradGuard no_grad;
    auto l = load(*f);
    std::vector<int64_t> training, held_out;
    for (int64_t i : all_episodes(l.demos))
      (vae::is_held_out(l.demos.episodes[i]) ? held_out : training).push_back(i);
    std::printf("RMS error of the mean action against the demonstration's, on its own states (action units):\n\n"
                "| demonstrations | z | first step | later steps |\n|---|---|---|---|\n");
    print_action_errors(l, training, "training experts");
    print_action_errors(l, held_out, "held-out experts");
  });
}

// ---- vae refit-policy -----------------------------------------------------------------
struct RefitFlags : ModelFlags {
  vae::PolicyRefitOptions refit;
  double state_std_floor = -1;
  std::string z_from;
};

// Each episode's first context component (the style of a humanoid demonstration); a file without
// contexts cannot lend z by label.
std::vector<double> style_labels(const DemoSet& demos, const std::vector<int64_t>& episodes) {
  std::vector<double> labels;
  for (int64_t i : episodes) {
    if (demos.episodes[i].context.empty()) throw std::invalid_argument(demos.path + ": episodes without a context");
    labels.push_back(demos.episodes[i].context[0]);
  }
  return labels;
}

bool same_directory(const std::string& a, const std::string& b) {
  std::error_code ignored;
  return fs::exists(a) && fs::exists(b) && fs::equivalent(a, b, ignored);
}

void run_refit_policy(const RefitFlags& f) {
  const fs::path checkpoint_dir = fs::is_directory(f.checkpoint) ? fs::path(f.checkpoint) : fs::path(f.checkpoint).parent_path();
  if (same_directory(checkpoint_dir.string(), f.refit.out_dir) ||
      same_directory(checkpoint_dir.parent_path().string(), f.refit.out_dir))
    throw std::invalid_argument("--out-dir " + f.refit.out_dir + " is the VAE's own run directory: refit into another");
  auto l = load(f);
  if (f.state_std_floor >= 0) l.model->set_policy_state_std_floor(f.state_std_floor);
  auto data = vae::make_demo_training_data(std::move(l.demos), l.model->config(), f.refit.seed);
  torch::Tensor train_mu, val_mu;
  if (f.z_from.empty()) {  // each demonstration's own mu
    Progress progress("encode", static_cast<std::int64_t>(data.train.size() + data.val.size()), "demos");
    train_mu = vae::encode(l.model, data.train).first;
    progress.advance(data.train.size());
    if (data.val.size() > 0) val_mu = vae::encode(l.model, data.val).first;
    progress.finish();
  } else {
    const auto clean = read_demos(f.z_from);
    require_dims_match(l.model, clean);
    const auto clean_mu = encode_with_progress(l.model, clean, all_episodes(clean));
    const auto source = style_labels(clean, all_episodes(clean));
    train_mu = vae::latents_by_label(clean_mu, source, style_labels(data.demos, data.split.train), f.refit.seed);
    if (data.val.size() > 0)
      val_mu = vae::latents_by_label(clean_mu, source, style_labels(data.demos, data.split.val), f.refit.seed + 1);
    std::printf("z: each demonstration's borrowed from a demonstration of its context in %s\n", f.z_from.c_str());
  }
  const auto train = vae::step_records(l.model, data.train, train_mu);
  const auto val = data.val.size() > 0 ? vae::step_records(l.model, data.val, val_mu) : vae::StepRecords{};
  std::printf("%lld training steps (%zu episodes), %lld validation steps (%zu episodes)\n",
              static_cast<long long>(train.size()), data.split.train.size(), static_cast<long long>(val.size()),
              data.split.val.size());
  const auto r = vae::refit_policy(l.model, train, val, f.refit);
  std::printf("action NLL per step (normalised units) / RMSE (action units), before -> after %d epochs:\n"
              "  train %.3f / %.4f -> %.3f / %.4f\n  val   %.3f / %.4f -> %.3f / %.4f\n",
              r.epochs_run, r.before_train.nll, r.before_train.rmse, r.train.nll, r.train.rmse, r.before_val.nll,
              r.before_val.rmse, r.val.nll, r.val.rmse);
  std::printf("weights: %s\n", (fs::path(f.refit.out_dir) / kWeightsFile).c_str());
}

void add_refit_policy(CLI::App& vae) {
  auto f = std::make_shared<RefitFlags>();
  CLI::App* c = vae.add_subcommand(
      "refit-policy",
      "train the VAE's action decoder further on single steps, encoder and state decoder frozen "
      "(z: each demonstration's mu); rerun to resume");
  add_model_flags(*c, *f);
  c->add_option("--out-dir", f->refit.out_dir, "weights.pt (the whole VAE), metrics.csv, checkpoints/latest.pt")->required();
  c->add_option("--epochs", f->refit.epochs, "passes over the training steps")->check(CLI::Range(1, 1 << 20))->capture_default_str();
  c->add_option("--batch-size", f->refit.batch, "steps per Adam step")->check(CLI::Range(1, 1 << 24))->capture_default_str();
  c->add_option("--lr", f->refit.learning_rate, "Adam learning rate, cosine-decayed to 1/100 of it")
      ->check(CLI::PositiveNumber)->capture_default_str();
  c->add_option("--seed", f->refit.seed, "shuffling; and the validation split, as `vae train --seed`")->capture_default_str();
  c->add_option("--state-std-floor", f->state_std_floor,
                "floor on the state std the action decoder's input is divided by (VaeConfig's "
                "policy_state_std_floor; default: the checkpoint's)")
      ->check(CLI::NonNegativeNumber);
  c->add_option("--z-from", f->z_from,
                "demonstration file (the clean ones) whose encodings lend z: each refit demonstration takes "
                "the mu of a random one of the same context, instead of its own (for noise-perturbed "
                "demonstrations the encoder never saw)")
      ->check(CLI::ExistingFile);
  c->callback([f] { run_refit_policy(*f); });
}

// ---- vae imitate ----------------------------------------------------------------------
struct ImitateFlags {
  ModelFlags model;
  std::string episodes = "all", out;
  bool held_out_only = false;
  vae::ImitationOptions rollout;
};

// "all", or N episodes spread evenly over the selection (so every expert is represented).
std::vector<int64_t> choose_episodes(const DemoSet& demos, const std::string& which, bool held_out_only) {
  std::vector<int64_t> pool;
  for (int64_t i = 0; i < static_cast<int64_t>(demos.episodes.size()); ++i)
    if (!held_out_only || vae::is_held_out(demos.episodes[i])) pool.push_back(i);
  if (pool.empty()) throw std::invalid_argument(demos.path + ": no episodes to imitate" + (held_out_only ? " (none held out)" : ""));
  if (which == "all") return pool;
  int64_t n = 0;
  try {
    size_t used = 0;
    n = std::stoll(which, &used);
    if (used != which.size() || n < 1) throw std::invalid_argument(which);
  } catch (const std::exception&) {
    throw std::invalid_argument("--episodes must be 'all' or a positive count, not '" + which + "'");
  }
  if (n >= static_cast<int64_t>(pool.size())) return pool;
  std::vector<int64_t> chosen;
  for (int64_t j = 0; j < n; ++j) chosen.push_back(pool[j * static_cast<int64_t>(pool.size()) / n]);
  return chosen;
}

void run_imitate(const ImitateFlags& f) {
  torch::NoGradGuard no_grad;
  auto l = load(f.model);
  const auto episodes = choose_episodes(l.demos, f.episodes, f.held_out_only);
  const auto z = encode_with_progress(l.model, l.demos, episodes);
  const auto env = demo_env(l.demos, l.model);
  Progress progress("imitate", static_cast<std::int64_t>(episodes.size()), "episodes");
  const auto outcomes = vae::roll_out_latent_policy(*env, vae::rollout_starts(l.demos, episodes), z,
                                                    vae::vae_mean_policy(l.model, l.device), f.rollout, &progress);
  progress.finish();
  std::vector<double> demo_speed, imitation_speed;
  int falls = 0;
  std::string csv = "episode,expert_id,context,held_out,demo_speed,imitation_speed,abs_diff,fell,steps\n";
  for (size_t j = 0; j < episodes.size(); ++j) {
    const Episode& e = l.demos.episodes[episodes[j]];
    const auto& o = outcomes[j];
    demo_speed.push_back(vae::achieved_speed(l.demos, episodes[j]));
    imitation_speed.push_back(o.achieved_speed);
    falls += o.fell;
    fmt::format_to(std::back_inserter(csv), "{},{},{:.9g},{},{:.6f},{:.6f},{:.6f},{},{}\n", episodes[j], e.expert_id,
                   e.context.empty() ? std::nan("") : e.context[0], vae::is_held_out(e) ? 1 : 0, demo_speed.back(),
                   o.achieved_speed, std::abs(demo_speed.back() - o.achieved_speed), o.fell ? 1 : 0, o.episode.length());
  }
  if (!f.out.empty()) write_file_atomically(f.out, csv);
  std::printf("imitated %zu demonstrations%s: median |speed difference| %.3f m/s, fall rate %.1f%%%s%s\n",
              episodes.size(), f.held_out_only ? " (held out)" : "",
              vae::median_abs_difference(demo_speed, imitation_speed), 100.0 * falls / episodes.size(),
              f.out.empty() ? "" : "; per episode: ", f.out.c_str());
}

void add_imitate(CLI::App& vae) {
  auto f = std::make_shared<ImitateFlags>();
  CLI::App* c = vae.add_subcommand("imitate", "encode demonstrations and roll out the VAE policy's mean action from their initial states");
  add_model_flags(*c, f->model);
  c->add_option("--episodes", f->episodes, "'all' or N spread evenly over the file")->capture_default_str();
  c->add_flag("--held-out-only", f->held_out_only, "only episodes with held_out = 1 (one-shot imitation)");
  c->add_option("--out", f->out, "per-episode CSV: demo and imitation speed, |difference|, fell");
  c->add_option("--envs", f->rollout.num_envs, "environments stepped together")->check(CLI::Range(1, 1 << 20))->capture_default_str();
  c->add_option("--threads", f->rollout.num_threads, "threads stepping them")->check(CLI::Range(1, 1 << 10))->capture_default_str();
  c->callback([f] { run_imitate(*f); });
}

// ---- vae interpolate ------------------------------------------------------------------
struct InterpolateFlags {
  ModelFlags model;
  std::string pair;
  std::vector<double> alphas{0, 0.25, 0.5, 0.75, 1};
};

std::pair<int64_t, int64_t> parse_pair(const std::string& text, int64_t episodes) {
  const auto comma = text.find(',');
  try {
    size_t used_i = 0, used_j = 0;
    const int64_t i = std::stoll(text.substr(0, comma), &used_i);
    const int64_t j = std::stoll(text.substr(comma + 1), &used_j);
    if (comma == std::string::npos || used_i != comma || used_j != text.size() - comma - 1) throw std::invalid_argument(text);
    if (i < 0 || j < 0 || i >= episodes || j >= episodes)
      throw std::out_of_range("--pair " + text + ": episodes are 0.." + std::to_string(episodes - 1));
    return {i, j};
  } catch (const std::out_of_range& e) {
    throw std::invalid_argument(e.what());
  } catch (const std::exception&) {
    throw std::invalid_argument("--pair must be I,J (two episode indices), not '" + text + "'");
  }
}

void run_interpolate(const InterpolateFlags& f) {
  torch::NoGradGuard no_grad;
  auto l = load(f.model);
  const auto [i, j] = parse_pair(f.pair, static_cast<int64_t>(l.demos.episodes.size()));
  const auto mu = encode_with_progress(l.model, l.demos, {i, j});
  std::vector<torch::Tensor> zs;
  for (double a : f.alphas) zs.push_back((1 - a) * mu[0] + a * mu[1]);
  const auto env = demo_env(l.demos, l.model);
  // Every alpha starts from demonstration I's initial state, so only z differs.
  const std::vector<vae::RolloutStart> starts(f.alphas.size(), vae::rollout_starts(l.demos, {i})[0]);
  Progress progress("interpolate", static_cast<std::int64_t>(f.alphas.size()), "rollouts");
  const auto outcomes = vae::roll_out_latent_policy(*env, starts, torch::stack(zs), vae::vae_mean_policy(l.model, l.device),
                                                    {}, &progress);
  progress.finish();
  std::printf("demo %lld speed %.3f m/s, demo %lld speed %.3f m/s\n", static_cast<long long>(i),
              vae::achieved_speed(l.demos, i), static_cast<long long>(j), vae::achieved_speed(l.demos, j));
  std::printf("alpha  achieved_speed  fell\n");
  for (size_t a = 0; a < f.alphas.size(); ++a)
    std::printf("%5.2f  %14.3f  %4s\n", f.alphas[a], outcomes[a].achieved_speed, outcomes[a].fell ? "yes" : "no");
}

void add_interpolate(CLI::App& vae) {
  auto f = std::make_shared<InterpolateFlags>();
  CLI::App* c = vae.add_subcommand("interpolate", "roll out the VAE policy at z = (1 - alpha) mu_I + alpha mu_J");
  add_model_flags(*c, f->model);
  c->add_option("--pair", f->pair, "I,J: episode indices in the demonstration file")->required();
  c->add_option("--alphas", f->alphas, "comma-separated blend weights")->delimiter(',')->capture_default_str();
  c->callback([f] { run_interpolate(*f); });
}

// ---- bench vae ------------------------------------------------------------------------
struct BenchFlags {
  std::string preset = "walker";
  int state_dim = 0, action_dim = 0, steps = 0;  // 0: the preset body's
  int trainer_batches = 0;                      // 0: the step and its parts, not the trainer
  std::string json;
  VaeBenchOptions bench;
};

// Each preset's body and data set: its observation and action sizes, episode length and the
// number of training episodes an epoch is projected for (walker: 60 experts x 20 episodes).
struct BenchShape {
  int state_dim, action_dim, steps, epoch_episodes;
};
BenchShape bench_shape(const std::string& preset) {
  if (preset == "arm" || preset == "jaco") return {21, 9, 50, 1800};
  if (preset == "humanoid") return {137, 56, 334, 250};
  return {18, 6, 400, 1200};
}

void add_bench_vae(CLI::App& bench) {
  auto f = std::make_shared<BenchFlags>();
  CLI::App* c = bench.add_subcommand("vae", "VAE training throughput vs this machine's sgemm; fused WaveNet kernel vs conv1d");
  c->add_option("--preset", f->preset, "network sizes of the paper's Table 1")
      ->check(CLI::IsMember({"walker", "arm", "jaco", "humanoid"}))->capture_default_str();
  c->add_option("--state-dim", f->state_dim, "state components (default: the preset body's: walker 18, arm 21, humanoid 137)")
      ->check(CLI::Range(1, 1 << 16));
  c->add_option("--action-dim", f->action_dim, "action components (default: walker 6, arm 9, humanoid 56)")->check(CLI::Range(1, 1 << 16));
  c->add_option("--batch", f->bench.batch, "trajectories per step")->check(CLI::Range(1, 1 << 16))->capture_default_str();
  c->add_option("--steps", f->steps, "steps per trajectory (default: the preset body's episode: 400, 50, 334)")->check(CLI::Range(1, 1 << 20));
  c->add_option("--seconds", f->bench.seconds, "measuring time per part (after one untimed run)")
      ->check(CLI::Range(0.0, 3600.0))->capture_default_str();
  c->add_option("--trainer-batches", f->trainer_batches,
                "instead, time `vae train` itself: two epochs of this many batches on random trajectories "
                "(under mpirun: the ranks together; scripts/bench/vae_ranks.sh)")
      ->check(CLI::Range(1, 1 << 20));
  auto* json = c->add_option("--json", f->json, "with --trainer-batches, also write the figures to this JSON file");
  json->needs(c->get_option("--trainer-batches"));
  c->callback([f] {
    const BenchShape shape = bench_shape(f->preset);
    f->bench.steps = f->steps ? f->steps : shape.steps;
    f->bench.epoch_steps = shape.steps;
    f->bench.epoch_episodes = shape.epoch_episodes;
    f->bench.config = vae::VaeConfig::preset(f->preset, f->state_dim ? f->state_dim : shape.state_dim,
                                             f->action_dim ? f->action_dim : shape.action_dim);
    if (f->trainer_batches > 0) {
      const auto r = run_vae_trainer_bench(f->bench, f->trainer_batches);
      std::fputs(format_vae_trainer_bench(f->bench, r).c_str(), stdout);
      if (!f->json.empty() && World::get().is_root())
        write_file_atomically(f->json, vae_trainer_bench_json(f->bench, r).dump(2) + "\n");
      return;
    }
    const auto r = run_vae_bench(f->bench);
    std::fputs(format_vae_bench(f->bench, r).c_str(), stdout);
  });
}

}  // namespace

void add_vae_commands(CLI::App& app) {
  CLI::App* vae = app.add_subcommand("vae", "trajectory VAE: train, embed, knn, imitate, interpolate");
  vae->require_subcommand(1);
  add_train(*vae);
  add_embed(*vae);
  add_knn(*vae);
  add_action_error(*vae);
  add_refit_policy(*vae);
  add_imitate(*vae);
  add_interpolate(*vae);
  add_bench_vae(*app.get_subcommand("bench"));  // add_bench_commands runs first
}

}  // namespace vaegail::cli
