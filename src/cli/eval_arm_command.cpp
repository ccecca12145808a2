// `vaegail eval arm`: the paper's arm experiment (section 4.1). The VAE policy imitates the
// test experts' demonstrations (and some training ones) from the home pose; the end effector's
// final distance to the demonstration's end point is summarised (Figure 2's paths drawn), and
// pairs of test (or training) demonstrations from different experts are interpolated in latent space
// (Figure 3), each pair judged by whether its reached end points move monotonically along the
// segment between the demonstrations' end points. With --gail the diverse-GAIL policy fine-tuned
// on the same VAE imitates instead, from the same z; with --joint-blend no model does, and the
// same measurements are taken of interpolating the demonstrations' final joint commands.
#include <torch/torch.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <memory>

#include "cli/commands.h"
#include "cli/figures.h"
#include "cli/imitation_video.h"
#include "cli/task_options.h"
#include "eval/arm_eval.h"
#include "eval/walker_eval.h"
#include "gail/diverse_gail.h"
#include "util/atomic_file.h"
#include "util/progress.h"
#include "vae/demo_dataset.h"
#include "vae/latent_refinement.h"
#include "vae/vae_trainer.h"

namespace vaegail::cli {

namespace fs = std::filesystem;

namespace {

struct EvalArmFlags {
  std::string demos, vae, gail, out_dir, device = "cpu", pairs_from = "test";
  int training_per_expert = 3, pair_experts = 10, drawn_paths = 10, drawn_pairs = 3;
  double monotone_tolerance = 0.0;
  bool joint_blend = false;
  vae::ImitationOptions rollout;
  vae::RefineOptions refine{0, 0.05, 64};  // 0 steps: the encoder's mean, as the paper
  int videos = 0;
  render::VideoOptions video;
};

// The paper's Figure 3 blend weights.
const std::vector<double> kAlphas{0.0, 0.25, 0.5, 0.75, 1.0};

// z of each episode (by index into the episodes), and where it came from, for the report.
class Embeddings {
 public:
  Embeddings(std::vector<int64_t> episodes, torch::Tensor z, std::string source)
      : episodes_(std::move(episodes)), z_(std::move(z)), source_(std::move(source)) {}
  const std::string& source() const { return source_; }
  torch::Tensor of(const std::vector<int64_t>& episodes) const {
    std::vector<int64_t> rows;
    for (int64_t e : episodes)
      rows.push_back(std::find(episodes_.begin(), episodes_.end(), e) - episodes_.begin());
    return z_.index_select(0, torch::tensor(rows));
  }

 private:
  std::vector<int64_t> episodes_;
  torch::Tensor z_;
  std::string source_;
};

// The encoder's mean, refined when asked.
Embeddings encoded(vae::TrajectoryVae& model, const DemoSet& demos, std::vector<int64_t> episodes,
                   const vae::RefineOptions& refine) {
  torch::Tensor z = vae::encode_episodes(model, demos, episodes);
  if (refine.steps == 0) return Embeddings(std::move(episodes), z, "the encoder's mean");
  const auto data = vae::to_trajectory_dataset(demos, episodes, model->config());
  auto refined = vae::refine_with_report(model, data, z, refine);
  return Embeddings(std::move(episodes), refined.z, refined.description);
}

// The reference without a VAE: an episode's "embedding" is the last joint command it recorded,
// and the policy holds it. Blending two of them is interpolation in joint space, what a latent
// that encoded only the final pose would give; how the hand's end point moves along it is a
// property of the experts' poses and the arm, not of any model.
Embeddings final_commands(const DemoSet& demos, std::vector<int64_t> episodes) {
  const int64_t act_dim = demos.header.act_dim();
  torch::Tensor z = torch::empty({static_cast<int64_t>(episodes.size()), act_dim});
  for (size_t i = 0; i < episodes.size(); ++i) {
    const auto& actions = demos.episodes[episodes[i]].actions;
    z[i] = torch::tensor(std::vector<float>(actions.end() - act_dim, actions.end()));
  }
  return Embeddings(std::move(episodes), z, "each demonstration's last joint command (joint-space reference, no VAE)");
}

// Every episode of the experts marked held out, in file order.
std::vector<int64_t> held_out_episodes(const DemoSet& demos) {
  std::vector<int64_t> out;
  for (size_t i = 0; i < demos.episodes.size(); ++i)
    if (vae::is_held_out(demos.episodes[i])) out.push_back(static_cast<int64_t>(i));
  if (out.empty()) throw std::invalid_argument(demos.path + ": no episode is marked held_out (the test experts)");
  return out;
}

std::vector<int64_t> training_episodes(const DemoSet& demos, int per_expert) {
  std::vector<int64_t> out;
  for (int64_t i : eval::episodes_per_expert(demos, per_expert))
    if (!vae::is_held_out(demos.episodes[i])) out.push_back(i);
  return out;
}

// The first demonstration in `pool` of each of its first `experts` experts, every pair of them.
std::vector<std::pair<int64_t, int64_t>> expert_pairs(const DemoSet& demos, const std::vector<int64_t>& pool, int experts) {
  std::vector<int64_t> firsts;
  std::map<std::string, bool> seen;
  for (int64_t i : pool)
    if (!seen[demos.episodes[i].expert_id] && static_cast<int>(firsts.size()) < experts) {
      seen[demos.episodes[i].expert_id] = true;
      firsts.push_back(i);
    }
  std::vector<std::pair<int64_t, int64_t>> pairs;
  for (size_t a = 0; a < firsts.size(); ++a)
    for (size_t b = a + 1; b < firsts.size(); ++b) pairs.push_back({firsts[a], firsts[b]});
  return pairs;
}

std::string distance_line(const std::string& which, const std::vector<eval::ReachRow>& rows, bool held_out) {
  std::vector<double> d;
  for (const auto& r : rows)
    if (r.held_out == held_out) d.push_back(r.final_distance());
  const auto s = eval::summarize_distances(d);
  return fmt::format("| {} | {} | {:.1f} | {:.1f} | {:.1f} |\n", which, s.n, 100 * s.mean, 100 * s.median, 100 * s.p90);
}

std::string interpolation_summary(const std::vector<eval::InterpolationPair>& pairs, const std::string& pool,
                                  double tolerance) {
  int monotone = 0;
  std::vector<double> off, off_relative, mid_along;
  for (const auto& p : pairs) {
    monotone += p.monotone(tolerance);
    for (size_t k = 0; k < p.alphas.size(); ++k) {
      off.push_back(p.off_line[k]);
      off_relative.push_back(p.off_line[k] / p.segment_length());
      if (p.alphas[k] == 0.5) mid_along.push_back(p.along[k]);
    }
  }
  const std::string text = fmt::format(
      "Latent interpolation over {} pairs of {} demonstrations (different experts), alpha in "
      "{{0, 0.25, 0.5, 0.75, 1}}:\n\n"
      "- end point moves monotonically from a's end to b's (tolerance {:.2f} of the segment): **{} of {} "
      "pairs ({:.0f}%)**\n"
      "- distance of the reached end points from the line through the two demonstrations' end points: "
      "median {:.1f} cm, 90th percentile {:.1f} cm (median {:.0f}% of the segment's length)\n"
      "- at alpha 0.5 the end point lies at median s = {:.2f} along the segment (0: a's end, 1: b's end)\n",
      pairs.size(), pool, tolerance, monotone, pairs.size(), 100.0 * monotone / std::max<size_t>(pairs.size(), 1),
      100 * vae::median(off), 100 * eval::summarize_distances(off).p90, 100 * vae::median(off_relative),
      vae::median(mid_along));
  // The α steps of a short segment are no longer than the imitation error itself.
  const std::vector<double> edges{0.2, 0.4};
  const auto bins = eval::monotone_by_segment_length(pairs, tolerance, edges);
  std::string by_length = "- monotone by segment length:";
  const char* names[] = {"under 20 cm", "20 to 40 cm", "40 cm or more"};
  for (size_t i = 0; i < bins.size(); ++i)
    by_length += fmt::format("{} {} {} of {}", i ? ";" : "", names[i], bins[i].first, bins[i].second);
  return text + by_length + "\n";
}

// STEM.csv (scripts/plot/paths.py's columns), and STEM.png drawn from it when matplotlib is there.
void draw_paths(const std::string& stem, const std::string& csv, const std::string& title, const std::string& colormap) {
  write_file_atomically(stem + ".csv", csv);
  draw_figure_if_possible("paths.py", {"--csv", stem + ".csv", "--colormap", colormap, "--title", title, "--xlabel",
                                       "grip x (m)", "--ylabel", "grip y (m)", "--out", stem + ".png"});
}

// --videos N: the first N pairs, each as one row: demonstration a, the policy at every blend of
// their z (from a's start, as the measurement), demonstration b.
void write_interpolation_videos(const Env& env, const DemoSet& demos, const std::vector<std::pair<int64_t, int64_t>>& pairs,
                                const Embeddings& z, const vae::LatentPolicy& policy, const EvalArmFlags& f) {
  const std::string dir = f.out_dir + "/videos";
  fs::create_directories(dir);
  for (size_t p = 0; p < std::min<size_t>(f.videos, pairs.size()); ++p) {
    const auto [a, b] = pairs[p];
    std::vector<torch::Tensor> blends;
    std::vector<std::string> captions;
    for (double alpha : kAlphas) {
      blends.push_back((1 - alpha) * z.of({a})[0] + alpha * z.of({b})[0]);
      captions.push_back(fmt::format("alpha {:.2f}", alpha));
    }
    std::vector<render::Clip> row{demo_clip(demos, a)};
    const std::vector<int64_t> starts(kAlphas.size(), a);
    for (auto& clip : rollout_clips(env, vae::rollout_starts(demos, starts), torch::stack(blends), policy, captions))
      row.push_back(std::move(clip));
    row.push_back(demo_clip(demos, b));
    write_video(env, {row}, f.video, dir + "/interpolation_pair_" + std::to_string(p) + ".mp4");
  }
}

void run_eval_arm(const EvalArmFlags& f) {
  torch::NoGradGuard no_grad;
  const auto device = parse_device(f.device);
  if (!f.joint_blend && f.vae.empty()) throw std::invalid_argument("--vae is required (or --joint-blend)");
  if (!f.vae.empty() && !fs::exists(f.vae)) throw std::invalid_argument(f.vae + ": no such VAE checkpoint");
  const DemoSet demos = read_demos(f.demos);
  if (demos.header.env_id != "arm") throw std::invalid_argument(f.demos + ": recorded in '" + demos.header.env_id + "', not the arm");
  vae::TrajectoryVae model{nullptr};
  if (!f.joint_blend) {
    model = vae::load_trained_vae(f.vae, device);
    model->eval();
  }
  const auto env = f.joint_blend ? demo_env(demos) : demo_env(demos, model);
  const auto policy = f.joint_blend    ? eval::kHoldZAsCommand
                      : f.gail.empty() ? vae::vae_mean_policy(model, device)
                                       : agent_mean_policy(load_gail_agent(f.gail, env->obs_dim(), env->act_dim(),
                                                                           model, device));

  const auto test = held_out_episodes(demos);
  auto episodes = training_episodes(demos, f.training_per_expert);
  episodes.insert(episodes.end(), test.begin(), test.end());
  const auto pairs = expert_pairs(demos, f.pairs_from == "test" ? test : training_episodes(demos, 1), f.pair_experts);
  std::vector<int64_t> a, b, embedded = episodes;
  for (const auto& [i, j] : pairs) {
    a.push_back(i);
    b.push_back(j);
    for (int64_t e : {i, j})
      if (std::find(embedded.begin(), embedded.end(), e) == embedded.end()) embedded.push_back(e);
  }
  const Embeddings z = f.joint_blend ? final_commands(demos, embedded) : encoded(model, demos, embedded, f.refine);
  Progress progress("eval arm", static_cast<std::int64_t>(episodes.size()), "rollouts");
  const auto rows = eval::imitate_reaches(*env, demos, episodes, z.of(episodes), policy, f.rollout, &progress);
  progress.finish();
  const auto interpolations = eval::interpolate_reaches(*env, demos, pairs, z.of(a), z.of(b), kAlphas, policy,
                                                        f.rollout);

  fs::create_directories(f.out_dir);
  const std::string table =
      "policy: " + (f.joint_blend    ? std::string("holds z as its joint command")
                    : f.gail.empty() ? std::string("the VAE's mean action")
                                     : "the mean action of " + f.gail) +
      "\nz: " + z.source() + "\n\n"
      "Final end-effector distance between the policy's imitation and the demonstration (cm):\n\n"
      "| demonstrations | n | mean | median | 90th percentile |\n|---|---|---|---|---|\n" +
      distance_line("test experts (unseen)", rows, true) + distance_line("training experts", rows, false) + "\n" +
      interpolation_summary(interpolations, f.pairs_from + " experts'", f.monotone_tolerance);
  write_file_atomically(f.out_dir + "/reaches.csv", eval::reach_rows_csv(rows));
  write_file_atomically(f.out_dir + "/interpolation.csv", eval::interpolation_csv(interpolations));
  write_file_atomically(f.out_dir + "/summary.md", table);

  // Figure 2: one test demonstration per test expert and its imitation.
  std::vector<eval::ReachRow> drawn;
  std::map<std::string, bool> seen;
  for (const auto& r : rows)
    if (r.held_out && !seen[r.expert_id] && static_cast<int>(drawn.size()) < f.drawn_paths) {
      seen[r.expert_id] = true;
      drawn.push_back(r);
    }
  draw_paths(f.out_dir + "/reach_paths", eval::reach_paths_csv(drawn), "test demos (solid), imitations (dashed)",
             "tab10");
  for (int p = 0; p < std::min<int>(f.drawn_pairs, interpolations.size()); ++p)
    draw_paths(f.out_dir + "/interpolation_pair_" + std::to_string(p),
               eval::interpolation_paths_csv(interpolations[p], demos),
               "latent interpolation, pair " + std::to_string(p), "viridis");
  std::printf("\n%s\nwrote %s/{reaches.csv, interpolation.csv, summary.md, reach_paths.{csv,png}, "
              "interpolation_pair_*.{csv,png}}\n", table.c_str(), f.out_dir.c_str());
  if (f.videos > 0) write_interpolation_videos(*env, demos, pairs, z, policy, f);
}

}  // namespace

void add_eval_arm(CLI::App& eval) {
  auto f = std::make_shared<EvalArmFlags>();
  CLI::App* c = eval.add_subcommand("arm", "imitate the arm's test demonstrations with the VAE policy (final "
                                           "end-point distance) and interpolate between them in latent space");
  c->add_option("--demos", f->demos, "arm demonstration file (.h5) with the test experts marked held_out")->required();
  auto* vae = c->add_option("--vae", f->vae, "VAE run: its directory, checkpoints/latest.pt or weights.pt");
  auto* gail = c->add_option("--gail", f->gail,
                              "a diverse-GAIL run (directory, checkpoint or weights.pt) on the same VAE: its policy "
                              "imitates instead of the VAE's");
  auto* blend = c->add_flag("--joint-blend", f->joint_blend,
                            "reference without a VAE: z is each demonstration's last joint command and the policy holds "
                            "it, so interpolation blends the two final commands in joint space");
  blend->excludes(vae)->excludes(gail);
  c->add_option("--out-dir", f->out_dir, "where the CSVs, the table and the PNGs go")->required();
  c->add_option("--training-per-expert", f->training_per_expert, "training demonstrations imitated per expert, for comparison")
      ->check(CLI::Range(0, 1 << 20))->capture_default_str();
  c->add_option("--pairs-from", f->pairs_from, "whose demonstrations are interpolated: the test experts' or the training experts'")
      ->check(CLI::IsMember({"test", "training"}))->capture_default_str();
  c->add_option("--pair-experts", f->pair_experts, "experts whose first demonstrations are paired (all pairs)")
      ->check(CLI::Range(2, 1000))->capture_default_str();
  c->add_option("--monotone-tolerance", f->monotone_tolerance, "allowed step back along the segment, as a fraction of it")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  auto* refine = add_refine_options(*c, f->refine, "each demonstration's z");
  blend->excludes(refine);
  c->add_option("--envs", f->rollout.num_envs, "environments stepped together")->check(CLI::Range(1, 1 << 20))->capture_default_str();
  c->add_option("--videos", f->videos, "also write this many MP4s to OUT_DIR/videos, one per interpolated pair: "
                                       "demonstration a, a tile per blend weight, demonstration b")
      ->check(CLI::Range(0, 1 << 20))->capture_default_str();
  add_video_options(*c, f->video);
  add_device_option(*c, f->device);
  c->callback([f] { run_eval_arm(*f); });
}

}  // namespace vaegail::cli
