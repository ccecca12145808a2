#include "bench/physics_bench.h"

#include <torch/torch.h>

#include <algorithm>
#include <chrono>
#include <fmt/format.h>
#include <thread>
#include <vector>

#include "env/mujoco_env.h"
#include "env/vec_env.h"
#include "util/rng.h"

namespace vaegail {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace

double raw_physics_steps_per_s(const MujocoEnv& env, double seconds) {
  const mjModel* m = env.model();
  MjDataPtr data(mj_makeData(m));
  Rng rng(0);
  const int frame_skip = static_cast<int>(env.control_timestep() / m->opt.timestep + 0.5);
  long steps = 0;
  const auto start = Clock::now();
  do {
    mj_resetData(m, data.get());
    for (int t = 0; t < env.episode_length(); ++t) {
      for (int a = 0; a < m->nu; ++a) data->ctrl[a] = rng.uniform(-1, 1);
      for (int k = 0; k < frame_skip; ++k) mj_step(m, data.get());
      steps += frame_skip;
    }
  } while (since(start) < seconds);
  return steps / since(start);
}

namespace {

// raw_physics_steps_per_s on `cores` threads at the same time, summed.
double all_core_physics_steps_per_s(const MujocoEnv& env, double seconds, int cores) {
  std::vector<double> rates(cores);
  std::vector<std::thread> threads;
  for (int c = 0; c < cores; ++c)
    threads.emplace_back([&, c] { rates[c] = raw_physics_steps_per_s(env, seconds); });
  for (auto& t : threads) t.join();
  double sum = 0;
  for (double r : rates) sum += r;
  return sum;
}

}  // namespace

PhysicsBenchResult run_physics_bench(const PhysicsBenchOptions& options) {
  EnvRequest request = options.env;
  request.terminate_on_fall = false;  // same episode schedule as the raw loop
  auto env = make_env(request);
  const auto* mj_env = dynamic_cast<const MujocoEnv*>(env.get());
  if (!mj_env) throw std::invalid_argument("bench physics needs a MuJoCo environment");
  PhysicsBenchResult r;
  r.raw_physics_steps_per_s = raw_physics_steps_per_s(*mj_env, options.seconds);
  const int frame_skip = static_cast<int>(env->control_timestep() / mj_env->model()->opt.timestep + 0.5);
  r.raw_control_steps_per_s = r.raw_physics_steps_per_s / frame_skip;
  r.cores = options.cores > 0 ? options.cores : std::max(1u, std::thread::hardware_concurrency());
  r.all_core_control_steps_per_s = all_core_physics_steps_per_s(*mj_env, options.seconds, r.cores) / frame_skip;

  torch::NoGradGuard no_grad;
  torch::manual_seed(0);
  torch::nn::Sequential policy(torch::nn::Linear(env->obs_dim(), options.hidden), torch::nn::Tanh(),
                               torch::nn::Linear(options.hidden, options.hidden), torch::nn::Tanh(),
                               torch::nn::Linear(options.hidden, env->act_dim()), torch::nn::Tanh());
  VecEnv vec(*env, options.num_envs, options.threads);
  vec.set_auto_reset(true);
  std::vector<std::uint64_t> seeds;
  for (int i = 0; i < vec.size(); ++i) seeds.push_back(i);
  vec.reset(seeds);
  std::vector<float> obs(vec.observations());
  long steps = 0;
  double policy_seconds = 0;
  const auto start = Clock::now();
  do {
    const auto t0 = Clock::now();
    torch::Tensor input = torch::from_blob(obs.data(), {vec.size(), vec.obs_dim()});
    torch::Tensor actions = policy->forward(input).contiguous();
    policy_seconds += since(t0);
    vec.step(actions.data_ptr<float>());
    obs = vec.observations();
    steps += vec.size();
  } while (since(start) < options.seconds);
  const double elapsed = since(start);
  r.vec_control_steps_per_s = steps / elapsed;
  r.policy_fraction = policy_seconds / elapsed;
  return r;
}

std::string format_physics_bench(const PhysicsBenchOptions& o, const PhysicsBenchResult& r) {
  return fmt::format(
      "task                         {}\n"
      "raw mj_step                  {:.0f} physics steps/s = {:.0f} control steps/s (1 core)\n"
      "raw mj_step, every core      {:.0f} control steps/s ({} cores at once)\n"
      "VecEnv + MLP policy          {:.0f} control steps/s ({} envs, {} thread{}, 2x{} tanh; {:.0f}% of time in the policy)\n"
      "ratio policy loop / raw      {:.3f}{}\n",
      o.env.task, r.raw_physics_steps_per_s, r.raw_control_steps_per_s, r.all_core_control_steps_per_s, r.cores,
      r.vec_control_steps_per_s, o.num_envs, o.threads, o.threads == 1 ? "" : "s", o.hidden, 100 * r.policy_fraction,
      r.ratio(),
      o.threads == 1 ? (r.ratio() >= 0.7 ? "   (target >= 0.7 on one core: met)" : "   (target >= 0.7 on one core: NOT met)")
                     : "   (several threads: compare with the one-core ceiling x threads)");
}

}  // namespace vaegail
