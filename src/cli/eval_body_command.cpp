// `vaegail eval body`: the evaluation of any body (eval/body_eval.h): the VAE policy and the
// fine-tuned policies imitate demonstrations; falls and feature errors against them.
#include <torch/torch.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "cli/commands.h"
#include "cli/eval_policies.h"
#include "cli/task_options.h"
#include "eval/body_eval.h"
#include "util/atomic_file.h"
#include "util/progress.h"
#include "vae/vae_trainer.h"

namespace vaegail::cli {

namespace {

struct EvalBodyFlags {
  EvalInputs inputs;
  std::string out_dir, task, device = "cpu";
  int per_expert = 5;
  vae::ImitationOptions rollout;
};

void run_eval_body(const EvalBodyFlags& f) {
  torch::NoGradGuard no_grad;
  const auto device = parse_device(f.device);
  auto setup = load_eval_setup(f.inputs, device);
  const DemoSet& demos = setup.demos;
  check_demo_task(demos, f.task);
  auto& model = setup.model;
  const auto& env = setup.env;
  const auto& policies = setup.policies;

  const auto episodes = eval::episodes_per_expert(demos, f.per_expert);
  const auto z = vae::encode_episodes(model, demos, episodes);
  Progress progress("eval body", static_cast<std::int64_t>(episodes.size() * policies.size()), "rollouts");
  const auto result = eval::evaluate_body(*env, demos, episodes, z, policies, f.rollout, &progress);
  progress.finish();
  const std::string table = eval::body_summary_table(result);
  std::filesystem::create_directories(f.out_dir);
  write_file_atomically(f.out_dir + "/imitation.csv", eval::body_rows_csv(result));
  write_file_atomically(f.out_dir + "/summary.md", table);
  std::printf("%s: %zu demonstrations imitated from their initial states; feature errors are mean |imitation - "
              "demonstration| per step\n\n%s\nwrote %s/{imitation.csv, summary.md}\n",
              env->id().c_str(), episodes.size(), table.c_str(), f.out_dir.c_str());
}

}  // namespace

void add_eval_body(CLI::App& eval) {
  auto f = std::make_shared<EvalBodyFlags>();
  CLI::App* c = eval.add_subcommand("body", "any body: imitate demonstrations with the VAE and fine-tuned policies; "
                                            "falls and per-feature errors against the demonstrations");
  add_eval_input_options(*c, f->inputs);
  c->add_option("--per-expert", f->per_expert, "demonstrations per expert id")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  c->add_option("--out-dir", f->out_dir, "where imitation.csv and summary.md go")->required();
  c->add_option("--envs", f->rollout.num_envs, "environments stepped together")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  add_demo_task_option(*c, f->task);
  add_device_option(*c, f->device);
  c->callback([f] { run_eval_body(*f); });
}

}  // namespace vaegail::cli
