// vaegail: robust imitation of diverse behaviours (Wang, Merel et al. 2017) as one CLI.
#include <torch/torch.h>

#include <cstdio>

#include "cli/commands.h"

int main(int argc, char** argv) {
  CLI::App app{"vaegail: learn robust controllers of diverse behaviours from few demonstrations"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "help for every command");
  int torch_threads = 1;
  app.add_option("--torch-threads", torch_threads,
                 "threads per Torch op (one is fastest for this project's small models)")
      ->check(CLI::Range(1, 1 << 30))->capture_default_str();
  app.parse_complete_callback([&] { torch::set_num_threads(torch_threads); });
  vaegail::cli::add_env_commands(app);
  vaegail::cli::add_data_commands(app);
  vaegail::cli::add_expert_commands(app);
  vaegail::cli::add_bench_commands(app);
  vaegail::cli::add_vae_commands(app);  // after bench: adds `bench vae`
  vaegail::cli::add_quickstart_command(app);
  vaegail::cli::add_plot_commands(app);
  vaegail::cli::add_gail_commands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vaegail: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
