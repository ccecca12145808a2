// `vaegail eval humanoid`: the paper's Figure 5 right (eval/humanoid_eval.h). The VAE policy and
// the fine-tuned policies imitate the training controllers' demonstrations and, one-shot, the
// evaluation controllers'; falls before the episode's end (when), and whether the imitations that
// stayed up kept the demonstration's style; tables, a CSV, a JSON summary and the bar chart.
#include <torch/torch.h>

#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <stdexcept>

#include "cli/commands.h"
#include "cli/eval_policies.h"
#include "cli/figures.h"
#include "cli/task_options.h"
#include "eval/humanoid_eval.h"
#include "util/atomic_file.h"
#include "util/progress.h"
#include "vae/vae_trainer.h"

namespace vaegail::cli {

namespace fs = std::filesystem;

namespace {

struct EvalHumanoidFlags {
  EvalInputs inputs;
  std::string eval_demos, out_dir, device = "cpu";
  int per_style = 10;
  vae::ImitationOptions rollout;
};

// A demonstration file's episodes to imitate and their embeddings by the VAE (the training set's,
// whichever file they come from: one-shot for the evaluation set).
struct DemoSetToImitate {
  std::string set;
  const DemoSet* demos;
  std::vector<int64_t> episodes;
  torch::Tensor z;
};

void run_eval_humanoid(const EvalHumanoidFlags& f) {
  torch::NoGradGuard no_grad;
  const auto device = parse_device(f.device);
  auto setup = load_eval_setup(f.inputs, device);
  check_demo_task(setup.demos, "humanoid");
  const Env& env = *setup.env;
  DemoSet eval_demos;
  std::vector<DemoSetToImitate> sets = {{"train", &setup.demos, {}, {}}};
  if (!f.eval_demos.empty()) {
    eval_demos = read_demos(f.eval_demos);
    check_demo_task(eval_demos, "humanoid");
    demo_env(eval_demos, setup.model);  // the VAE's dimensions
    sets.push_back({"eval", &eval_demos, {}, {}});
  }
  std::int64_t rollouts = 0;
  for (auto& s : sets) {
    s.episodes = eval::episodes_per_expert(*s.demos, f.per_style);
    s.z = vae::encode_episodes(setup.model, *s.demos, s.episodes);
    rollouts += static_cast<std::int64_t>(s.episodes.size() * setup.policies.size());
  }

  Progress progress("eval humanoid", rollouts, "rollouts");
  std::vector<eval::HumanoidRow> rows;
  for (const auto& s : sets) {
    const auto set_rows =
        eval::evaluate_humanoid(env, *s.demos, s.set, s.episodes, s.z, setup.policies, f.rollout, &progress);
    rows.insert(rows.end(), set_rows.begin(), set_rows.end());
  }
  progress.finish();

  const auto summaries = eval::summarize_humanoid(rows);
  const double dt = env.control_timestep();
  std::string method = fmt::format(
      "Up to {} demonstrations per controller, each imitated from its initial state{} ({} control steps, {:.2f} s); "
      "the training set's embedded by the VAE{}. Fell: the body fell before the episode's end. Kept the style: the "
      "nearest-centroid gait classifier (experts/humanoid_gait.h), fitted on the whole episodes of the "
      "demonstration's own file, names the demonstration's controller from the imitation's gait signature; asked "
      "only of the imitations that stayed up to the end (a fall is not a gait).\n\n",
      f.per_style,
      f.rollout.start_seed == 0 ? "" : fmt::format(" (fresh initial states, start seed {})", f.rollout.start_seed),
      env.episode_length(), env.episode_length() * dt,
      f.eval_demos.empty() ? "" : ", the evaluation set's one-shot by the same VAE");
  const std::string table = method + eval::humanoid_table(summaries);
  fs::create_directories(f.out_dir);
  write_file_atomically(f.out_dir + "/imitation.csv", eval::humanoid_rows_csv(rows));
  write_file_atomically(f.out_dir + "/summary.md", table);
  write_file_atomically(f.out_dir + "/summary.json", eval::humanoid_json(summaries).dump(2) + "\n");
  std::printf("\n%s\nwrote %s/{imitation.csv, summary.md, summary.json}\n", table.c_str(), f.out_dir.c_str());

  const std::string figure = f.out_dir + "/falls.png";
  write_file_atomically(figure_data_path(figure), eval::humanoid_falls_csv(summaries));
  if (draw_figure_if_possible("bars.py", {"--csv", figure_data_path(figure), "--ylabel",
                                          "falls before the episode's end (%)", "--title",
                                          "humanoid: imitations that fall, per controller (Fig. 5 right)",
                                          "--out", figure}))
    std::printf("wrote %s\n", figure.c_str());
}

}  // namespace

void add_eval_humanoid(CLI::App& eval) {
  auto f = std::make_shared<EvalHumanoidFlags>();
  CLI::App* c = eval.add_subcommand(
      "humanoid", "the humanoid (the paper's Figure 5 right): imitate the training controllers' demonstrations and, "
                  "one-shot, the evaluation controllers'; falls (when) and whether the style is kept");
  add_eval_input_options(*c, f->inputs);
  c->add_option("--eval-demos", f->eval_demos,
                "the evaluation controllers' demonstrations (" + kHumanoidEvalDemos +
                    "): encoded by the VAE trained on --demos and imitated one-shot")
      ->check(CLI::ExistingFile);
  c->add_option("--episodes-per-style", f->per_style, "demonstrations per controller (the first of each)")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  c->add_option("--out-dir", f->out_dir, "where imitation.csv, summary.md, summary.json and falls.png go")->required();
  c->add_option("--envs", f->rollout.num_envs, "environments stepped together")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  c->add_option("--threads", f->rollout.num_threads, "threads stepping them")
      ->check(CLI::Range(1, 256))->capture_default_str();
  add_start_seed_option(*c, f->rollout);
  add_device_option(*c, f->device);
  c->callback([f] { run_eval_humanoid(*f); });
}

}  // namespace vaegail::cli
