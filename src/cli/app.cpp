#include "cli/app.h"

#include <torch/torch.h>

#include <cstdio>

#include "cli/commands.h"

namespace vaegail::cli {

std::unique_ptr<CLI::App> make_app() {
  auto app = std::make_unique<CLI::App>("vaegail: learn robust controllers of diverse behaviours from few demonstrations");
  app->require_subcommand(1);
  app->set_help_all_flag("--help-all", "help for every command");
  auto torch_threads = std::make_shared<int>(1);
  app->add_option("--torch-threads", *torch_threads,
                  "threads per Torch op (one is fastest for this project's small models)")
      ->check(CLI::Range(1, 1 << 30))->capture_default_str();
  app->parse_complete_callback([torch_threads] { torch::set_num_threads(*torch_threads); });
  add_env_commands(*app);
  add_data_commands(*app);
  add_expert_commands(*app);
  add_bench_commands(*app);
  add_vae_commands(*app);  // after bench: adds `bench vae`
  add_quickstart_command(*app);
  add_plot_commands(*app);
  add_gail_commands(*app);
  add_eval_commands(*app);
  add_render_commands(*app);  // after bench: adds `bench render`
  add_export_command(*app);
  return app;
}

void run_command_line(const std::string& line) {
  std::printf("\n$ vaegail %s\n", line.c_str());
  std::fflush(stdout);
  make_app()->parse(line, false);
}

}  // namespace vaegail::cli
