#include "data/record.h"

#include <algorithm>
#include <map>
#include <memory>
#include <mutex>

#include "util/progress.h"
#include "util/rng.h"
#include "util/thread_pool.h"

namespace vaegail {

DemoHeader header_for(const Env& env) {
  DemoHeader h;
  h.env_id = env.id();
  h.control_timestep = env.control_timestep();
  h.observation_names = env.observation_spec().names;
  h.action_names = env.action_spec().names;
  h.feature_names = env.feature_names();
  h.context_names = env.context_names();
  h.body_mjcf = env.body_mjcf();
  return h;
}

namespace {

void append_state(const Env& env, Episode& e, std::vector<float>& obs_row) {
  env.observe(obs_row.data());
  e.observations.insert(e.observations.end(), obs_row.begin(), obs_row.end());
  const size_t nf = env.feature_names().size();
  e.features.resize(e.features.size() + nf);
  env.features(e.features.data() + e.features.size() - nf);
}

}  // namespace

std::vector<Episode> record_episodes(const Env& prototype, const RecordRequest& request,
                                     const BatchPolicy& policy, Progress* progress) {
  const int total = static_cast<int>(request.seeds.size());
  if (!request.contexts.empty() && static_cast<int>(request.contexts.size()) != total)
    throw std::invalid_argument("record_episodes: one context per episode expected");
  const int slots = std::max(1, std::min(request.num_envs, total));
  const int obs_dim = prototype.obs_dim(), act_dim = prototype.act_dim();
  std::vector<std::unique_ptr<Env>> envs;
  for (int s = 0; s < slots; ++s) envs.push_back(prototype.clone());
  ThreadPool pool(std::min(request.num_threads, slots));
  std::vector<Episode> episodes(total);
  std::vector<int> running(slots, -1);  // episode index per slot, -1 when idle
  std::vector<std::vector<float>> obs_rows(slots, std::vector<float>(obs_dim));
  int next = 0, finished = 0;

  auto start = [&](int s) {
    if (next >= total) {
      running[s] = -1;
      return;
    }
    const int i = next++;
    Env& env = *envs[s];
    if (!request.contexts.empty()) env.set_context(request.contexts[i]);
    env.reset(request.seeds[i]);
    Episode& e = episodes[i];
    e.seed = request.seeds[i];
    e.context = env.context();
    e.expert_id = request.expert_id;
    append_state(env, e, obs_rows[s]);
    running[s] = i;
  };
  for (int s = 0; s < slots; ++s) start(s);

  const BoxSpec action_box = prototype.action_spec();
  EpisodeStreams execution_noise(request.execution_noise_seed);
  std::vector<float> batch_obs, batch_act, batch_executed;
  std::vector<int> batch_slots, batch_episodes, batch_steps;
  while (finished < total) {
    batch_slots.clear();
    batch_episodes.clear();
    batch_steps.clear();
    batch_obs.clear();
    for (int s = 0; s < slots; ++s) {
      if (running[s] < 0) continue;
      batch_slots.push_back(s);
      batch_episodes.push_back(running[s]);
      batch_steps.push_back(envs[s]->steps_taken());
      batch_obs.insert(batch_obs.end(), obs_rows[s].begin(), obs_rows[s].end());
    }
    const int n = static_cast<int>(batch_slots.size());
    batch_act.assign(static_cast<size_t>(n) * act_dim, 0.f);
    policy(n, batch_obs.data(), batch_episodes.data(), batch_steps.data(), batch_act.data());
    batch_executed = batch_act;
    if (request.execution_noise_std > 0)
      for (int b = 0; b < n; ++b) {
        Rng& rng = execution_noise(batch_episodes[b]);
        for (int a = 0; a < act_dim; ++a) {
          float& u = batch_executed[static_cast<size_t>(b) * act_dim + a];
          u = static_cast<float>(std::clamp(u + request.execution_noise_std * rng.normal(), action_box.low[a],
                                            action_box.high[a]));
        }
      }
    std::vector<std::uint8_t> done(n, 0);
    pool.parallel_for(n, [&](int b) {
      const int s = batch_slots[b];
      Env& env = *envs[s];
      Episode& e = episodes[running[s]];
      const float* action = &batch_act[static_cast<size_t>(b) * act_dim];
      const StepOutcome out = env.step(&batch_executed[static_cast<size_t>(b) * act_dim]);
      e.actions.insert(e.actions.end(), action, action + act_dim);
      e.rewards.push_back(out.reward);
      e.terminations.push_back(out.terminated);
      e.truncations.push_back(out.truncated);
      append_state(env, e, obs_rows[s]);
      done[b] = out.done();
    });
    for (int b = 0; b < n; ++b) {
      if (!done[b]) continue;
      const int s = batch_slots[b];
      Episode& e = episodes[running[s]];
      const int nf = static_cast<int>(prototype.feature_names().size());
      for (int f = 0; f < nf; ++f)
        e.attributes["mean_" + prototype.feature_names()[f]] = e.mean_feature(f, nf);
      ++finished;
      if (progress) progress->advance();
      start(s);
    }
  }
  return episodes;
}

BatchPolicy random_policy(const Env& env, std::uint64_t seed) {
  auto streams = std::make_shared<EpisodeStreams>(seed);
  const BoxSpec spec = env.action_spec();
  return [streams, spec](int n, const float*, const int* episodes, const int*, float* actions) {
    const int act_dim = spec.dim();
    for (int b = 0; b < n; ++b) {
      Rng& rng = (*streams)(episodes[b]);
      for (int a = 0; a < act_dim; ++a)
        actions[b * act_dim + a] = static_cast<float>(rng.uniform(spec.low[a], spec.high[a]));
    }
  };
}

BatchPolicy zero_policy(const Env& env) {
  const int act_dim = env.act_dim();
  return [act_dim](int n, const float*, const int*, const int*, float* actions) {
    std::fill(actions, actions + static_cast<size_t>(n) * act_dim, 0.f);
  };
}

BatchPolicy with_episode_offset(BatchPolicy policy, const BoxSpec& box, double std, std::uint64_t seed) {
  // Each episode's offset is the first draw of its own stream, kept until the episode ends.
  auto offsets = std::make_shared<std::map<int, std::vector<double>>>();
  return [policy = std::move(policy), box, std, seed, offsets](int n, const float* observations,
                                                               const int* episodes, const int* steps,
                                                               float* actions) {
    policy(n, observations, episodes, steps, actions);
    const int act_dim = box.dim();
    for (int b = 0; b < n; ++b) {
      auto [it, drawn] = offsets->try_emplace(episodes[b]);
      if (drawn) {
        Rng rng(derive_seed(seed, static_cast<std::uint64_t>(episodes[b])));
        for (int a = 0; a < act_dim; ++a) it->second.push_back(std * rng.normal());
      }
      for (int a = 0; a < act_dim; ++a) {
        float& u = actions[static_cast<size_t>(b) * act_dim + a];
        u = static_cast<float>(std::clamp(u + it->second[a], box.low[a], box.high[a]));
      }
    }
  };
}

}  // namespace vaegail
