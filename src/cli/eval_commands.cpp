// `vaegail eval walker`: the paper's walker evaluation (section 4.2, Figure 4 bottom right) of
// the VAE policy, the diverse-GAIL policy and the baselines, as a table, a CSV and histograms.
#include <torch/torch.h>

#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <stdexcept>

#include "cli/commands.h"
#include "cli/eval_policies.h"
#include "cli/figures.h"
#include "cli/imitation_video.h"
#include "cli/task_options.h"
#include "eval/walker_eval.h"
#include "gail/behavior_cloning.h"
#include "gail/diverse_gail.h"
#include "util/atomic_file.h"
#include "util/histogram.h"
#include "util/progress.h"
#include "vae/vae_trainer.h"

namespace vaegail::cli {

namespace fs = std::filesystem;

namespace {

struct EvalWalkerFlags {
  EvalInputs inputs;
  std::string out_dir, device = "cpu";
  int per_expert = 11;
  vae::ImitationOptions rollout;
  int videos = 0;
  render::VideoOptions video;
};

std::vector<double> column(const std::vector<eval::ImitationRow>& rows, const std::string& policy, bool held_out,
                           double (*value)(const eval::ImitationRow&)) {
  std::vector<double> out;
  for (const auto& r : rows)
    if (r.policy == policy && r.held_out == held_out) out.push_back(value(r));
  return out;
}

// The series' values as FIGURE.csv, their counts printed, and the figure drawn when matplotlib is there.
void save_histogram(const std::string& figure, const FigureLabels& labels, const std::vector<HistogramSeries>& series) {
  std::vector<HistogramSeries> drawn;
  for (const auto& s : series)
    if (!s.values.empty()) drawn.push_back(s);
  if (drawn.empty()) return;
  const int bins = 30;
  std::printf("\n%s\n%s", labels.title.c_str(), histogram_table(even_bin_edges(drawn, bins), drawn).c_str());
  save_histogram_figure(figure, drawn, bins, labels);
}

// --videos N: N of the imitated demonstrations, spread evenly over them (so over the experts),
// each beside every policy's imitation from its start.
void write_videos(const Env& env, const DemoSet& demos, const std::vector<int64_t>& episodes, const torch::Tensor& z,
                  const std::vector<eval::NamedPolicy>& policies, const EvalWalkerFlags& f) {
  const std::string dir = f.out_dir + "/videos";
  fs::create_directories(dir);
  const size_t n = std::min<size_t>(f.videos, episodes.size());
  for (size_t k = 0; k < n; ++k) {
    const size_t i = k * episodes.size() / n;
    const auto grid = imitation_grid(env, demos, {episodes[i]}, imitators(policies, z.narrow(0, i, 1)));
    write_video(env, grid, f.video, dir + "/demo_" + std::to_string(episodes[i]) + ".mp4");
  }
}

}  // namespace

std::vector<eval::NamedPolicy> load_policies(const vae::TrajectoryVae& model, const Env& env, const PolicyRuns& runs,
                                             torch::Device device) {
  std::vector<eval::NamedPolicy> policies;
  if (model) policies.push_back({"vae", vae::vae_mean_policy(model, device)});
  if (!runs.gail.empty())
    policies.push_back({"diverse_gail", agent_mean_policy(load_gail_agent(runs.gail, env.obs_dim(), env.act_dim(),
                                                                          model, device))});
  if (!runs.plain.empty())
    policies.push_back({"plain_gail", agent_mean_policy(load_gail_agent(runs.plain, env.obs_dim(), env.act_dim(),
                                                                        vae::TrajectoryVae(nullptr), device))});
  if (!runs.bc.empty())
    policies.push_back({"bc", agent_mean_policy(load_bc_agent(runs.bc, env.obs_dim(), env.act_dim(), device))});
  return policies;
}

void add_start_seed_option(CLI::App& command, vae::ImitationOptions& rollout) {
  command.add_option("--start-seed", rollout.start_seed,
                     "evaluation seed: 0, each rollout from its demonstration's own initial state (the published "
                     "figures); else from a fresh initial state drawn with this seed (the spread over seeds)")
      ->capture_default_str();
}

void add_eval_input_options(CLI::App& command, EvalInputs& inputs) {
  command.add_option("--demos", inputs.demos, "demonstration file (.h5); its body and task are rebuilt from it")
      ->required();
  command.add_option("--vae", inputs.vae, "VAE run (directory, checkpoints/latest.pt or weights.pt); encodes the demonstrations")
      ->required();
  command.add_option("--gail", inputs.runs.gail, "diverse-GAIL run (gail train --mode diverse): directory, checkpoint or weights.pt");
  command.add_option("--plain", inputs.runs.plain, "plain-GAIL run (gail train --mode plain): directory, checkpoint or weights.pt");
  command.add_option("--bc", inputs.runs.bc, "behaviour-cloning run (bc train): directory, checkpoint or weights.pt");
}

EvalSetup load_eval_setup(const EvalInputs& inputs, torch::Device device) {
  if (!fs::exists(inputs.vae)) throw std::invalid_argument(inputs.vae + ": no such VAE checkpoint");
  EvalSetup setup;
  setup.demos = read_demos(inputs.demos);
  setup.model = vae::load_trained_vae(inputs.vae, device);
  setup.model->eval();
  setup.env = demo_env(setup.demos, setup.model);
  setup.policies = load_policies(setup.model, *setup.env, inputs.runs, device);
  return setup;
}

namespace {

void run_eval_walker(const EvalWalkerFlags& f) {
  torch::NoGradGuard no_grad;
  const auto device = parse_device(f.device);
  auto setup = load_eval_setup(f.inputs, device);
  const DemoSet& demos = setup.demos;
  auto& model = setup.model;
  const auto& env = setup.env;
  const auto& policies = setup.policies;

  const auto episodes = eval::episodes_per_expert(demos, f.per_expert);
  const auto z = vae::encode_episodes(model, demos, episodes);
  Progress progress("eval walker", static_cast<std::int64_t>(episodes.size() * policies.size()), "rollouts");
  const auto rows = eval::imitate_with_policies(*env, demos, episodes, z, policies, f.rollout, &progress);
  progress.finish();

  fs::create_directories(f.out_dir);
  const auto modes = eval::mode_table(eval::mode_coverages(rows), eval::distinct_targets(rows));
  const eval::ModeCoverageOptions mode_rule;
  const std::string rule = fmt::format(
      "\nA target speed counts as a covered mode when at least {:.0f}% of the average speeds lie within {:.1f} m/s of it "
      "(training experts' demonstrations).\n\n",
      100 * mode_rule.min_fraction, mode_rule.radius);
  std::vector<eval::ImitationRow> training_rows;
  std::copy_if(rows.begin(), rows.end(), std::back_inserter(training_rows),
               [](const eval::ImitationRow& r) { return !r.held_out; });
  const std::string starts =
      f.rollout.start_seed == 0
          ? ""
          : fmt::format("Starts: fresh initial states (start seed {}), not the demonstrations' own.\n\n",
                        f.rollout.start_seed);
  const auto table = starts + eval::summary_table(eval::summarize(rows)) + "\nBy target speed:\n\n" +
                     eval::summary_table(eval::summarize(training_rows, /*by_target=*/true)) + rule + modes;
  write_file_atomically(f.out_dir + "/imitation.csv", eval::rows_csv(rows));
  write_file_atomically(f.out_dir + "/summary.md", table);

  const auto abs_diff = [](const eval::ImitationRow& r) { return r.abs_difference(); };
  const auto achieved = [](const eval::ImitationRow& r) { return r.achieved_speed; };
  const auto demo = [](const eval::ImitationRow& r) { return r.demo_speed; };
  for (const bool held_out : {false, true}) {
    std::vector<HistogramSeries> errors;
    for (const auto& p : policies) errors.push_back({p.name, column(rows, p.name, held_out, abs_diff)});
    const std::string which = held_out ? "one-shot (held out)" : "training experts";
    save_histogram(f.out_dir + (held_out ? "/speed_difference_held_out.png" : "/speed_difference.png"),
                   {"|demo - imitation speed|, " + which, "m/s", "demonstrations"}, errors);
  }
  std::vector<HistogramSeries> speeds{{"demonstrations", column(rows, "vae", false, demo)}};
  for (const auto& p : policies) speeds.push_back({p.name, column(rows, p.name, false, achieved)});
  save_histogram(f.out_dir + "/speeds.png", {"average speed: demonstrations and imitations", "m/s", "episodes"},
                 speeds);
  std::printf("\n%s\nwrote %s/{imitation.csv, summary.md, speed_difference, speed_difference_held_out, speeds}"
              ".{csv,png}\n", table.c_str(), f.out_dir.c_str());
  if (f.videos > 0) write_videos(*env, demos, episodes, z, policies, f);
}

void add_eval_walker(CLI::App& eval) {
  auto f = std::make_shared<EvalWalkerFlags>();
  CLI::App* c = eval.add_subcommand("walker", "imitate demonstrations with the VAE, diverse-GAIL and baseline "
                                              "policies; compare their speeds with the demonstrations'");
  add_eval_input_options(*c, f->inputs);
  c->add_option("--per-expert", f->per_expert, "demonstrations per expert (the paper: 11)")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  c->add_option("--out-dir", f->out_dir, "where the CSV, the table and the PNGs go")->required();
  c->add_option("--envs", f->rollout.num_envs, "environments stepped together")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  add_start_seed_option(*c, f->rollout);
  c->add_option("--videos", f->videos, "also write this many MP4s to OUT_DIR/videos: a demonstration beside each "
                                       "policy's imitation")
      ->check(CLI::Range(0, 1 << 20))->capture_default_str();
  add_video_options(*c, f->video);
  add_device_option(*c, f->device);
  c->callback([f] { run_eval_walker(*f); });
}

}  // namespace

void add_eval_commands(CLI::App& app) {
  CLI::App* eval = app.add_subcommand("eval", "the paper's evaluations");
  eval->require_subcommand(1);
  add_eval_walker(*eval);
  add_eval_arm(*eval);
  add_eval_body(*eval);
  add_eval_transitions(*eval);
  add_eval_humanoid(*eval);
}

}  // namespace vaegail::cli
