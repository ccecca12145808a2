// `vaegail eval transitions`: the paper's transition experiment (end of section 4.3,
// eval/transitions.h). Pairs of demonstrations (A, B): from A's initial state conditioned on z_A,
// blended to z_B over 20 control steps at mid-episode; whether each policy stays up and whether
// it then does what B does, as a CSV, tables, a figure of speed over time and videos.
#include <torch/torch.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <iterator>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>

#include "cli/commands.h"
#include "cli/eval_policies.h"
#include "cli/figures.h"
#include "cli/imitation_video.h"
#include "cli/task_options.h"
#include "eval/transitions.h"
#include "util/atomic_file.h"
#include "util/progress.h"

namespace vaegail::cli {

namespace fs = std::filesystem;

namespace {

struct EvalTransitionsFlags {
  EvalInputs inputs;
  std::string out_dir, device = "cpu";
  std::vector<int64_t> episodes;  // all ordered pairs over these; else a sample
  int pairs = 200, per_expert = 11, figure_pairs = 4;
  std::uint64_t seed = 0;
  double tolerance = 0.25;
  eval::TransitionOptions transition;
  int videos = 0;
  render::VideoOptions video;
};

std::vector<eval::TransitionPair> choose_pairs(const DemoSet& demos, const eval::BehaviourJudge& judge,
                                               const EvalTransitionsFlags& f) {
  if (!f.episodes.empty()) {
    for (const int64_t e : f.episodes)
      if (e < 0 || e >= static_cast<int64_t>(demos.episodes.size()))
        throw std::invalid_argument("--episodes: " + demos.path + " has no episode " + std::to_string(e) +
                                    " (it has " + std::to_string(demos.episodes.size()) + ", from 0)");
    return eval::all_ordered_pairs(f.episodes);
  }
  const auto pool = eval::episodes_per_expert(demos, f.per_expert);
  std::vector<std::string> labels;
  for (const int64_t e : pool) labels.push_back(judge.of_demonstration(demos, e).label);
  auto pairs = eval::sample_pairs(pool, labels, f.pairs, f.seed);
  if (pairs.empty())
    throw std::invalid_argument(demos.path + ": no pair of different " + judge.noun + "s among the " +
                                std::to_string(pool.size()) + " demonstrations sampled from");
  return pairs;
}

// z_A and z_B of every pair: each distinct episode encoded once.
std::pair<torch::Tensor, torch::Tensor> pair_latents(vae::TrajectoryVae& model, const DemoSet& demos,
                                                     const std::vector<eval::TransitionPair>& pairs) {
  std::vector<int64_t> episodes;
  for (const auto& p : pairs) episodes.insert(episodes.end(), {p.from, p.to});
  std::sort(episodes.begin(), episodes.end());
  episodes.erase(std::unique(episodes.begin(), episodes.end()), episodes.end());
  const auto z = vae::encode_episodes(model, demos, episodes);
  const auto rows_of = [&](int64_t eval::TransitionPair::*end) {
    std::vector<int64_t> rows;
    for (const auto& p : pairs)
      rows.push_back(std::lower_bound(episodes.begin(), episodes.end(), p.*end) - episodes.begin());
    return z.index_select(0, torch::tensor(rows));
  };
  return {rows_of(&eval::TransitionPair::from), rows_of(&eval::TransitionPair::to)};
}

std::string pair_title(const eval::TransitionRow& r, const std::string& noun) {
  const char* unit = noun == "speed" ? " m/s" : "";
  return fmt::format("#{} ({}{}) to #{} ({}{})", r.pair.from, r.from.label, unit, r.pair.to, r.to.label, unit);
}

// The pairs a figure or the videos show, with their latents and their demonstrations' behaviours.
struct Shown {
  std::vector<eval::TransitionPair> pairs;
  torch::Tensor z_from, z_to;  // [pairs, Z]
  std::vector<std::string> titles;
  std::vector<eval::Behaviour> from, to;
};

// Up to `count` pairs of different behaviours, one per (from, to) label first, so that they
// show different transitions. rows: run_transitions' (the first policy's come first).
Shown shown_pairs(const std::vector<eval::TransitionRow>& rows, const std::vector<eval::TransitionPair>& pairs,
                  const torch::Tensor& z_from, const torch::Tensor& z_to, int count, const std::string& noun) {
  std::vector<int64_t> index;
  std::set<std::pair<std::string, std::string>> seen;
  for (const bool repeat : {false, true})
    for (size_t i = 0; i < pairs.size() && static_cast<int>(index.size()) < count; ++i) {
      const auto& r = rows[i];
      if (!r.different() || std::find(index.begin(), index.end(), static_cast<int64_t>(i)) != index.end()) continue;
      if (seen.insert({r.from.label, r.to.label}).second || repeat) index.push_back(static_cast<int64_t>(i));
    }
  Shown s;
  for (const int64_t i : index) {
    s.pairs.push_back(pairs[i]);
    s.titles.push_back(pair_title(rows[i], noun));
    s.from.push_back(rows[i].from);
    s.to.push_back(rows[i].to);
  }
  s.z_from = z_from.index_select(0, torch::tensor(index));
  s.z_to = z_to.index_select(0, torch::tensor(index));
  return s;
}

// The forward speed per control step of each shown pair's rollouts beside the demonstrations'
// mean speeds, as panel,series,style,x,y; then the figure, the blend window shaded.
void write_speed_figure(const Env& env, const DemoSet& demos, const Shown& shown,
                        const std::vector<eval::NamedPolicy>& policies, const eval::BlendSchedule& blend,
                        const EvalTransitionsFlags& f) {
  const auto& names = env.feature_names();
  const auto speed_column = std::find(names.begin(), names.end(), f.transition.rollout.speed_feature);
  if (speed_column == names.end() || shown.pairs.empty()) return;
  const int speed = static_cast<int>(speed_column - names.begin()), n_features = static_cast<int>(names.size());
  const double dt = env.control_timestep(), end = env.episode_length() * dt;
  std::string csv = "panel,series,style,x,y\n";
  for (const auto& p : policies) {
    const auto outcomes = eval::roll_out_transitions(env, demos, shown.pairs, shown.z_from, shown.z_to, p.policy,
                                                     blend, f.transition.rollout);
    for (size_t k = 0; k < outcomes.size(); ++k)
      for (int t = 1; t <= outcomes[k].episode.length(); ++t)
        fmt::format_to(std::back_inserter(csv), "{},{},solid,{:.4f},{:.5f}\n", shown.titles[k], p.name, t * dt,
                       outcomes[k].episode.features[static_cast<size_t>(t) * n_features + speed]);
  }
  for (size_t k = 0; k < shown.pairs.size(); ++k) {
    for (const auto& [series, value] :
         {std::pair{"demonstration A", shown.from[k].speed}, {"demonstration B", shown.to[k].speed}})
      for (const double x : {0.0, end})
        fmt::format_to(std::back_inserter(csv), "{},{},dashed,{:.4f},{:.5f}\n", shown.titles[k], series, x, value);
  }
  const std::string figure = f.out_dir + "/speed_over_time.png";
  write_file_atomically(figure_data_path(figure), csv);
  const std::string shade = fmt::format("{:.4f},{:.4f}", blend.start * dt, blend.end() * dt);
  const std::string smooth = std::to_string(std::max(1, static_cast<int>(std::lround(1.0 / dt))));
  const std::string title = fmt::format(
      "forward speed through a transition (1 s running mean; blend shaded; measured from {:.2f} s)",
      (blend.end() + f.transition.settle) * dt);
  if (draw_figure_if_possible("timeseries.py", {"--csv", figure_data_path(figure), "--shade", shade, "--smooth",
                                                smooth, "--xlabel", "time (s)", "--ylabel", "forward speed (m/s)",
                                                "--title", title, "--out", figure, "--height", "720"}))
    std::printf("wrote %s\n", figure.c_str());
}

// --videos N: a row per shown pair: demonstrations A and B, then each policy's transition.
void write_videos(const Env& env, const DemoSet& demos, const Shown& shown,
                  const std::vector<eval::NamedPolicy>& policies, const eval::BlendSchedule& blend,
                  const EvalTransitionsFlags& f) {
  const std::string dir = f.out_dir + "/videos";
  fs::create_directories(dir);
  const auto captions = imitators(policies, shown.z_from);  // the policies' captions
  for (size_t k = 0; k < shown.pairs.size(); ++k) {
    const auto& pair = shown.pairs[k];
    std::vector<render::Clip> row{demo_clip(demos, pair.from), demo_clip(demos, pair.to)};
    for (size_t p = 0; p < policies.size(); ++p) {
      auto outcome = eval::roll_out_transitions(env, demos, {pair}, shown.z_from.narrow(0, k, 1),
                                                shown.z_to.narrow(0, k, 1), policies[p].policy, blend,
                                                f.transition.rollout);
      row.push_back({fmt::format("{}\nz_A to z_B at {:.1f} s", captions[p].caption, blend.start * env.control_timestep()),
                     std::move(outcome[0].episode)});
    }
    write_video(env, {row}, f.video,
                dir + "/pair_" + std::to_string(pair.from) + "_to_" + std::to_string(pair.to) + ".mp4");
  }
}

void run_eval_transitions(EvalTransitionsFlags f) {
  torch::NoGradGuard no_grad;
  const auto device = parse_device(f.device);
  auto setup = load_eval_setup(f.inputs, device);
  const Env& env = *setup.env;
  const auto judge = eval::behaviour_judge(env, setup.demos, f.tolerance);
  f.transition.rollout.speed_feature = judge.speed_feature;  // the task's, in the rollouts and the figure
  const auto sampled = choose_pairs(setup.demos, judge, f);
  const auto pairs = eval::with_references(sampled);
  const auto [z_from, z_to] = pair_latents(setup.model, setup.demos, pairs);

  Progress progress("eval transitions", static_cast<std::int64_t>(pairs.size() * setup.policies.size()), "rollouts");
  const auto rows =
      eval::run_transitions(env, setup.demos, pairs, z_from, z_to, setup.policies, judge, f.transition, &progress);
  progress.finish();

  const auto blend = eval::mid_episode_blend(env.episode_length(), f.transition.blend_width);
  const double dt = env.control_timestep();
  const int measured_from = blend.end() + f.transition.settle;
  const std::string method = fmt::format(
      "{} pairs (A, B) and {} references (B, B). From A's initial state conditioned on z_A; z blended "
      "linearly to z_B over control steps {}..{} ({:.2f}..{:.2f} s of {:.2f} s); the {} measured from step {} "
      "({:.2f} s, after {} settling steps) to the end. Matched B: stayed up to the end and {}.{}\n\n",
      sampled.size(), pairs.size() - sampled.size(), blend.start, blend.end() - 1, blend.start * dt, blend.end() * dt,
      env.episode_length() * dt, judge.noun, measured_from, measured_from * dt, f.transition.settle, judge.rule,
      f.transition.rollout.start_seed == 0
          ? ""
          : fmt::format(" Starts: fresh initial states (start seed {}), not the demonstrations' own.", f.transition.rollout.start_seed));
  const std::string table = method +
                            eval::transition_table(eval::summarize_transitions(rows), judge.noun) +
                            "\nBy " + judge.noun + " of A and of B (pairs of different " + judge.noun + "s):\n\n" +
                            eval::transition_table(eval::summarize_transitions(rows, /*by_labels=*/true), judge.noun);
  fs::create_directories(f.out_dir);
  write_file_atomically(f.out_dir + "/transitions.csv", eval::transitions_csv(rows));
  write_file_atomically(f.out_dir + "/summary.md", table);
  std::printf("\n%s\nwrote %s/{transitions.csv, summary.md}\n", table.c_str(), f.out_dir.c_str());

  write_speed_figure(env, setup.demos, shown_pairs(rows, pairs, z_from, z_to, f.figure_pairs, judge.noun),
                     setup.policies, blend, f);
  if (f.videos > 0)
    write_videos(env, setup.demos, shown_pairs(rows, pairs, z_from, z_to, f.videos, judge.noun), setup.policies,
                 blend, f);
}

}  // namespace

void add_eval_transitions(CLI::App& eval) {
  auto f = std::make_shared<EvalTransitionsFlags>();
  CLI::App* c = eval.add_subcommand(
      "transitions", "transitions between behaviours (the paper's section 4.3): condition on one demonstration's z, "
                     "blend to another's at mid-episode; does the policy stay up and take on the second behaviour?");
  add_eval_input_options(*c, f->inputs);
  c->add_option("--out-dir", f->out_dir, "where transitions.csv, summary.md and the figure go")->required();
  auto* episodes = c->add_option("--episodes", f->episodes,
                                 "run all ordered pairs over these episode indices (instead of a sample)");
  c->add_option("--pairs", f->pairs, "ordered pairs of different behaviours to sample")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str()->excludes(episodes);
  c->add_option("--per-expert", f->per_expert, "the sample's pairs are drawn among the first demonstrations of each "
                                               "expert, this many")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str()->excludes(episodes);
  c->add_option("--seed", f->seed, "seed of the sample of pairs")->capture_default_str()->excludes(episodes);
  c->add_option("--blend-steps", f->transition.blend_width, "control steps over which z moves from z_A to z_B")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  c->add_option("--settle", f->transition.settle, "control steps after the blend before the behaviour is measured")
      ->check(CLI::Range(0, 1 << 20))->capture_default_str();
  c->add_option("--tolerance", f->tolerance,
                "walker: the speed after the blend matches B's within this (m/s); the humanoid's style is named by "
                "its gait classifier")
      ->check(CLI::Range(0.0, 100.0))->capture_default_str();
  c->add_option("--envs", f->transition.rollout.num_envs, "environments stepped together")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  add_start_seed_option(*c, f->transition.rollout);
  c->add_option("--figure-pairs", f->figure_pairs, "pairs drawn in speed_over_time.png (0: no figure)")
      ->check(CLI::Range(0, 64))->capture_default_str();
  c->add_option("--videos", f->videos, "also write this many MP4s to OUT_DIR/videos: demonstrations A and B beside "
                                       "each policy's transition")
      ->check(CLI::Range(0, 64))->capture_default_str();
  add_video_options(*c, f->video);
  add_device_option(*c, f->device);
  c->callback([f] { run_eval_transitions(*f); });
}

}  // namespace vaegail::cli
