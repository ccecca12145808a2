#include <cstdio>

#include "cli/commands.h"
#include "data/demo_stats.h"

namespace vaegail::cli {

void add_data_commands(CLI::App& app) {
  CLI::App* data = app.add_subcommand("data", "inspect demonstration files");
  data->require_subcommand(1);
  auto path = std::make_shared<std::string>();
  CLI::App* info = data->add_subcommand("info", "episodes, lengths, counts per context and feature statistics");
  info->add_option("file", *path, "demonstration file (.h5)")->required();
  info->callback([path] {
    const DemoSet set = read_demos(*path);
    std::fputs(format_summary(set, summarize(set)).c_str(), stdout);
  });
}

}  // namespace vaegail::cli
