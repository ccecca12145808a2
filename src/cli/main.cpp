// vaegail: robust imitation of diverse behaviours (Wang, Merel et al. 2017) as one CLI.
#include <cstdio>

#include "cli/app.h"

int main(int argc, char** argv) {
  const auto app = vaegail::cli::make_app();
  try {
    app->parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app->exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vaegail: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
