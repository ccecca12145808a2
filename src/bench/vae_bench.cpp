#include "bench/vae_bench.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fmt/format.h>

#include "util/malloc_tuning.h"
#include "util/world.h"
#include "vae/trajectory_vae.h"
#include "vae/vae_trainer.h"

namespace vaegail {

using vae::TrajectoryVae;
using vae::VaeConfig;

namespace {

using Clock = std::chrono::steady_clock;

// One untimed run (first-touch page faults, lazy initialisation), then runs until `seconds`
// have passed; the fastest run, which is the least disturbed by other processes.
template <class Fn>
double best_seconds(double seconds, const Fn& fn) {
  fn();
  double best = 1e300;
  const auto start = Clock::now();
  do {
    const auto t0 = Clock::now();
    fn();
    best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
  } while (std::chrono::duration<double>(Clock::now() - start).count() < seconds);
  return best;
}

double mm_gflops(int64_t m, int64_t k, int64_t n, double seconds) {
  const auto a = torch::randn({m, k}), b = torch::randn({k, n});
  auto out = torch::empty({m, n});
  const double s = best_seconds(seconds, [&] { torch::mm_out(out, a, b); });
  return 2.0 * m * k * n / s / 1e9;
}

double forward_backward_linear(double rows, double in, double out) { return 3.0 * 2.0 * rows * in * out; }

double peak_rss_mb() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return static_cast<double>(r.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

}  // namespace

double state_decoder_flops(const VaeConfig& c, double positions) {
  const double R = positions * c.state_dim, C = c.wavenet_channels, L = c.wavenet_layers;
  return L * (forward_backward_linear(R, 2 * C, 2 * C) + forward_backward_linear(R, C, 2 * C)) +
         forward_backward_linear(R, C, C) + forward_backward_linear(R, C, 3.0 * c.mixture_components) +
         forward_backward_linear(positions, c.state_dim + c.latent_dim, 2 * C * L);
}

VaeBenchResult run_vae_bench(const VaeBenchOptions& o) {
  retain_freed_memory();
  const VaeConfig& c = o.config;
  const int64_t B = o.batch, T = o.steps, D = c.state_dim, Z = c.latent_dim;
  VaeBenchResult r;
  r.threads = torch::get_num_threads();
  r.sgemm_model_gflops = mm_gflops(B * T * D, 2 * c.wavenet_channels, 2 * c.wavenet_channels, o.seconds);
  r.sgemm_square_gflops = mm_gflops(1024, 1024, 1024, o.seconds);

  torch::manual_seed(0);
  const auto states = torch::randn({B, T + 1, D}), actions = torch::randn({B, T, c.action_dim});
  const auto noise = torch::randn({B, Z});
  TrajectoryVae vae(c);
  vae->fit_normalization(states, actions);
  torch::optim::Adam adam(vae->parameters(), torch::optim::AdamOptions(c.learning_rate));

  r.step_seconds = best_seconds(o.seconds, [&] {
    adam.zero_grad();
    vae->loss(states, actions, {}, noise).total.backward();
    adam.step();
  });

  const auto x = vae->normalize_states(states).detach();
  const auto a = vae->normalize_actions(vae->modelled_actions(states, actions)).detach();
  const auto z_steps = noise.unsqueeze(1).expand({B, T, Z});
  r.encoder_seconds = best_seconds(o.seconds, [&] {
    vae->zero_grad();
    const auto q = vae->encoder()->forward(x);
    (q.mean.sum() + q.log_std.sum()).backward();
  });
  r.action_decoder_seconds = best_seconds(o.seconds, [&] {
    vae->zero_grad();
    vae->action_decoder()->log_prob(x.narrow(1, 0, T), z_steps, a).sum().neg().backward();
  });

  const auto prev = x.narrow(1, 0, T).reshape({B * T, D});
  const auto next = x.narrow(1, 1, T).reshape({B * T, D});
  const auto z_flat = z_steps.reshape({B * T, Z});
  r.state_decoder_seconds = best_seconds(o.seconds, [&] {
    vae->zero_grad();
    vae->state_decoder()->log_prob(prev, next, z_flat).sum().neg().backward();
  });
  r.state_decoder_gflops = state_decoder_flops(c, static_cast<double>(B * T)) / r.state_decoder_seconds / 1e9;
  r.reference_state_decoder_seconds = best_seconds(o.seconds, [&] {
    vae->zero_grad();
    vae::mixture_log_prob(next, vae->state_decoder()->forward_reference(prev, next, z_flat)).sum().neg().backward();
  });
  r.peak_rss_mb = peak_rss_mb();
  return r;
}

std::string format_vae_bench(const VaeBenchOptions& o, const VaeBenchResult& r) {
  const double epoch = r.epoch_seconds(o);
  return fmt::format(
      "VAE '{}' (LSTM {}, z {}, WaveNet {} x {} ch, K {}), batch {} x {} steps, {} torch thread{}\n"
      "sgemm ceiling          {:.1f} GFLOP/s [{} x {}] x [{} x {}] (state decoder's GEMM), {:.1f} GFLOP/s 1024^3\n"
      "training step          {:.3f} s (forward + backward + Adam) = {:.0f} trajectory-steps/s\n"
      "  encoder (BiLSTM)     {:.3f} s forward + backward\n"
      "  action decoder       {:.3f} s\n"
      "  state decoder        {:.3f} s = {:.1f} GFLOP/s = {:.0f}% of the sgemm ceiling\n"
      "conv1d reference       {:.3f} s state decoder alone: the fused kernel is {:.1f}x faster\n"
      "peak RSS               {:.0f} MB\n"
      "projected epoch        {:.1f} s for {} episodes x {} steps (target < {:.0f} s: {})\n",
      o.config.name, o.config.lstm_hidden, o.config.latent_dim, o.config.wavenet_layers,
      o.config.wavenet_channels, o.config.mixture_components, o.batch, o.steps, r.threads,
      r.threads == 1 ? "" : "s", r.sgemm_model_gflops, o.batch * o.steps * o.config.state_dim,
      2 * o.config.wavenet_channels, 2 * o.config.wavenet_channels, 2 * o.config.wavenet_channels,
      r.sgemm_square_gflops, r.step_seconds, r.steps_per_second(o), r.encoder_seconds,
      r.action_decoder_seconds, r.state_decoder_seconds, r.state_decoder_gflops,
      100.0 * r.state_decoder_gflops / r.sgemm_model_gflops, r.reference_state_decoder_seconds,
      r.reference_state_decoder_seconds / r.state_decoder_seconds, r.peak_rss_mb, epoch,
      o.epoch_episodes, o.epoch_steps, o.epoch_target_seconds,
      epoch < o.epoch_target_seconds ? "met" : "NOT met");
}

VaeTrainerBenchResult run_vae_trainer_bench(const VaeBenchOptions& o, int batches) {
  if (batches < 1) throw std::invalid_argument("bench vae: --trainer-batches must be at least 1");
  const World& world = World::get();
  // One run directory for all ranks: rank 0's process id names it.
  std::uint64_t id = static_cast<std::uint64_t>(::getpid());
  world.broadcast(&id, 1);
  const auto run_dir = std::filesystem::temp_directory_path() / ("vaegail_bench_vae_" + std::to_string(id));
  if (world.is_root()) std::filesystem::remove_all(run_dir);

  vae::VaeConfig c = o.config;
  c.batch_size = o.batch;
  c.lr_decay_epochs = 0;
  const int64_t M = static_cast<int64_t>(batches) * o.batch, T = o.steps;
  torch::manual_seed(0);
  vae::TrajectoryDataset data{torch::randn({M, T + 1, c.state_dim}), torch::randn({M, T, c.action_dim}), {}};
  vae::TrainerOptions options;
  options.run_dir = run_dir.string();
  options.epochs = 2;
  options.progress = false;
  VaeTrainerBenchResult r;
  r.ranks = world.size();
  r.batches = batches;
  {
    vae::VaeTrainer trainer(c, options, data, {});
    const auto epochs = trainer.train();
    r.seconds = std::min(epochs.front().train_seconds, epochs.back().train_seconds);
  }
  world.barrier();  // every rank is done with the run directory
  if (world.is_root()) std::filesystem::remove_all(run_dir);
  return r;
}

std::string format_vae_trainer_bench(const VaeBenchOptions& o, const VaeTrainerBenchResult& r) {
  return fmt::format(
      "VAE '{}' trainer (LSTM {}, z {}, WaveNet {} x {} ch), {} rank{} x {} torch thread{}, batch {} x {} steps\n"
      "epoch of {} batches    {:.2f} s (the faster of two) = {:.0f} trajectory-steps/s\n",
      o.config.name, o.config.lstm_hidden, o.config.latent_dim, o.config.wavenet_layers, o.config.wavenet_channels,
      r.ranks, r.ranks == 1 ? "" : "s", torch::get_num_threads(), torch::get_num_threads() == 1 ? "" : "s", o.batch,
      o.steps, r.batches, r.seconds, r.trajectory_steps_per_s(o));
}

nlohmann::json vae_trainer_bench_json(const VaeBenchOptions& o, const VaeTrainerBenchResult& r) {
  return {{"preset", o.config.name},     {"ranks", r.ranks},
          {"torch_threads", torch::get_num_threads()}, {"batch", o.batch},
          {"steps", o.steps},            {"batches", r.batches},
          {"seconds", r.seconds},        {"trajectory_steps_per_s", r.trajectory_steps_per_s(o)}};
}

}  // namespace vaegail
