// Each stage registers its subcommands on the `vaegail` app. A command's callback throws on
// bad input; main() turns that into one line on stderr and a non-zero exit.
#pragma once

#include <CLI/CLI.hpp>

namespace vaegail::cli {

void add_env_commands(CLI::App& app);
void add_data_commands(CLI::App& app);  // data info/import/export
void add_bench_commands(CLI::App& app);
void add_expert_commands(CLI::App& app);  // experts train/eval/tune, demos collect
void add_experts_tune(CLI::App& experts);
void add_quickstart_command(CLI::App& app);
void add_vae_commands(CLI::App& app);  // vae train/embed/knn/imitate/interpolate, bench vae
void add_plot_commands(CLI::App& app);  // plot curves/tsne/histogram
void add_gail_commands(CLI::App& app);  // gail train, bc train
void add_eval_commands(CLI::App& app);  // eval walker/arm/body/transitions/humanoid
void add_eval_arm(CLI::App& eval);
void add_eval_body(CLI::App& eval);
void add_eval_transitions(CLI::App& eval);
void add_eval_humanoid(CLI::App& eval);
void add_render_commands(CLI::App& app);  // render, bench render
void add_export_command(CLI::App& app);  // export: a run's weights file

struct TaskOptions;
// Flags every command that simulates shares: which task, and how episodes end.
void add_task_options(CLI::App& command, TaskOptions& options);

}  // namespace vaegail::cli
